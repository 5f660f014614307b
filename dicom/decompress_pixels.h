#pragma once
// Compressed pixel data -> uncompressed, in place (PACS and modality files often come
// JPEG Lossless, JPEG-LS or RLE encoded). Internal to dicom/ (includes DCMTK).
//
// Inputs   ds: a fully loaded dataset (pixel data included); path: the file, for messages.
// Output   OK with ds's pixel data in Explicit VR Little Endian when it was encapsulated in a
//          transfer syntax DCMTK decodes here: JPEG baseline, extended and lossless (dcmjpeg),
//          JPEG-LS (dcmjpls), RLE (dcmdata); OK and nothing done when it was not encapsulated.
// Errors   UNIMPLEMENTED naming the file and the transfer syntax when no decoder is available
//          (JPEG 2000, MPEG, HTJ2K), with a tool to convert it first; DATA_LOSS when decoding
//          fails (corrupt stream), with DCMTK's reason.
// Cost     O(pixels). Thread-safe: the decoders are registered once, process-wide.

#include "core/base/status.h"
#include "dicom/dcmtk_file.h"

namespace soiq::dicom {

Status decompress_pixels(DcmDataset& ds, const std::string& path);

}  // namespace soiq::dicom
