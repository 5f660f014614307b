#include "dicom/decompress_pixels.h"

#include <dcmtk/dcmdata/dccodec.h>
#include <dcmtk/dcmdata/dcrledrg.h>
#include <dcmtk/dcmjpeg/djdecode.h>
#include <dcmtk/dcmjpls/djdecode.h>

#include <mutex>

namespace soiq::dicom {
namespace {

// DCMTK's codec registry is global; registering twice would add the codecs twice. Never
// unregistered: the decoders live as long as the process.
void register_decoders() {
  static std::once_flag once;
  std::call_once(once, [] {
    DJDecoderRegistration::registerCodecs();
    DJLSDecoderRegistration::registerCodecs();
    DcmRLEDecoderRegistration::registerCodecs();
  });
}

}  // namespace

Status decompress_pixels(DcmDataset& ds, const std::string& path) {
  const DcmXfer xfer(ds.getOriginalXfer());
  if (!xfer.isEncapsulated()) return ok_status();
  register_decoders();
  const OFCondition cond = ds.chooseRepresentation(EXS_LittleEndianExplicit, nullptr);
  if (cond.good() && ds.canWriteXfer(EXS_LittleEndianExplicit)) return ok_status();
  const std::string name = xfer.getXferName();
  // DCMTK answers EC_CannotChangeRepresentation both when no codec handles the syntax and when
  // the codec failed on the stream: which one it was, the codec list says.
  if (!DcmCodecList::canChangeCoding(ds.getOriginalXfer(), EXS_LittleEndianExplicit))
    return Status(StatusCode::kUnimplemented, "'" + path + "': compressed pixel data (" + name +
                                                  ") has no decoder here (JPEG, JPEG-LS and RLE do); convert the "
                                                  "file first, e.g. with gdcmconv --raw");
  return condition_status(StatusCode::kDataLoss, path, "cannot decode its " + name + " pixel data (corrupt stream?)",
                          cond.good() ? EC_CannotChangeRepresentation : cond);
}

}  // namespace soiq::dicom
