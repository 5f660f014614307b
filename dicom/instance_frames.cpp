#include "dicom/instance_frames.h"

#include "dicom/dcmtk_file.h"
#include "dicom/decompress_pixels.h"

namespace soiq::dicom {

Result<std::vector<std::string>> instance_frames(const std::string& part10, std::vector<int64_t> frames) {
  SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<DcmFileFormat> file, parse_part10(part10));
  DcmDataset& ds = *file->getDataset();
  if (!ds.tagExistsWithValue(DCM_PixelData)) return not_found("the instance has no Pixel Data");
  Uint16 rows = 0, columns = 0, bits = 0, samples = 1;
  ds.findAndGetUint16(DCM_Rows, rows);
  ds.findAndGetUint16(DCM_Columns, columns);
  ds.findAndGetUint16(DCM_BitsAllocated, bits);
  if (ds.findAndGetUint16(DCM_SamplesPerPixel, samples).bad() || samples == 0) samples = 1;
  if (bits == 1)
    return Status(StatusCode::kUnimplemented,
                  "the instance's frames are 1 bit per pixel and not byte-aligned; retrieve the whole instance");
  if (rows == 0 || columns == 0 || bits == 0 || bits % 8 != 0)
    return Status(StatusCode::kDataLoss, "the instance's Rows, Columns or Bits Allocated (" + std::to_string(rows) +
                                             ", " + std::to_string(columns) + ", " + std::to_string(bits) +
                                             ") do not describe whole-byte frames");
  Sint32 count = 1;
  if (ds.findAndGetSint32(DCM_NumberOfFrames, count).bad() || count < 1) count = 1;
  if (frames.empty())
    for (Sint32 f = 1; f <= count; ++f) frames.push_back(f);
  for (const int64_t f : frames)
    if (f < 1 || f > count)
      return not_found("frame " + std::to_string(f) + " not found: the instance has " + std::to_string(count) +
                       (count == 1 ? " frame" : " frames"));
  SOIQ_RETURN_IF_ERROR(decompress_pixels(ds, "the instance"));
  // DCMTK hands OW values out only as 16-bit words (in this machine's byte order, little endian
  // on every target soiq builds for) and OB only as bytes.
  DcmElement* element = nullptr;
  const char* pixels = nullptr;
  if (ds.findAndGetElement(DCM_PixelData, element).good() && element != nullptr) {
    if (element->getVR() == EVR_OW) {
      Uint16* words = nullptr;
      if (element->getUint16Array(words).good()) pixels = reinterpret_cast<const char*>(words);
    } else {
      Uint8* bytes = nullptr;
      if (element->getUint8Array(bytes).good()) pixels = reinterpret_cast<const char*>(bytes);
    }
  }
  if (pixels == nullptr) return Status(StatusCode::kDataLoss, "the instance's Pixel Data cannot be read");
  const unsigned long length = element->getLength();
  const uint64_t frame_bytes = uint64_t(rows) * columns * samples * (bits / 8);
  if (uint64_t(length) < frame_bytes * uint64_t(count))
    return Status(StatusCode::kDataLoss, "the instance's Pixel Data holds " + std::to_string(length) +
                                             " bytes, less than " + std::to_string(count) + " frames of " +
                                             std::to_string(frame_bytes));
  std::vector<std::string> out;
  out.reserve(frames.size());
  for (const int64_t f : frames) out.emplace_back(pixels + frame_bytes * uint64_t(f - 1), frame_bytes);
  return out;
}

}  // namespace soiq::dicom
