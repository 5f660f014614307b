// The frames of a binary SEG as read_seg_file reads them: the Pixel Data checked against the
// header and unpacked by soiq (seg_bit_packing.h), each frame's plane checked against the grid and
// mapped to a slice, and a segment's frames turned into runs.

#include "dicom/read_seg_frames.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "dicom/dcmtk_file.h"
#include "dicom/decompress_pixels.h"
#include "dicom/seg_bit_packing.h"

namespace soiq::dicom {
namespace {

// Tolerances of a frame against the grid: positions as slice_stack accepts slices (max(0.01 mm,
// 1% of the spacing)), direction cosines as validate_geometry, pixel spacing as DS values written
// with 6 significant digits by other tools.
constexpr double kOrientationTolerance = 1e-4;
constexpr double kSpacingRelativeTolerance = 1e-4;
double position_tolerance_mm(double spacing_mm) { return std::max(0.01, 0.01 * spacing_mm); }

// The most pixels a Pixel Data value can hold at one bit each: its length field is 32 bits (even).
constexpr int64_t kMaxPixelDataBits = 8 * 0xFFFFFFFELL;

std::string vec_text(double x, double y, double z) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
}

}  // namespace

Result<BinaryPixels> binary_pixels(DcmDataset& ds, const std::string& path, const std::string& seg) {
  const std::string type = get_string(ds, DCM_SegmentationType);
  if (type == "FRACTIONAL") return invalid_argument(seg + " is a FRACTIONAL segmentation; only BINARY ones are read");
  if (type != "BINARY")
    return invalid_argument(seg + " has Segmentation Type '" + type + "'; only BINARY segmentations are read");
  Uint16 bits = 0, rows = 0, columns = 0;
  if (ds.findAndGetUint16(DCM_BitsAllocated, bits).bad() || bits != 1)
    return invalid_argument(seg + " has Bits Allocated " + std::to_string(bits) +
                            "; a BINARY segmentation has 1 bit per pixel");
  (void)ds.findAndGetUint16(DCM_Rows, rows);  // absent stays 0, refused next
  (void)ds.findAndGetUint16(DCM_Columns, columns);
  if (rows == 0 || columns == 0)
    return invalid_argument(seg + " has frames of Rows " + std::to_string(rows) + " x Columns " +
                            std::to_string(columns) + "; each needs at least 1");
  BinaryPixels out;
  out.rows = rows;
  out.columns = columns;
  const std::string frames_text = get_string(ds, DCM_NumberOfFrames);
  char* end = nullptr;
  const long long frames = std::strtoll(frames_text.c_str(), &end, 10);
  if (frames_text.empty() || *end != '\0' || frames < 1)
    return invalid_argument(seg + " has NumberOfFrames '" + frames_text + "'; a SEG needs at least 1 frame");
  // Bounded before anything is sized by it; the length check below bounds it by the file too.
  if (frames > kMaxPixelDataBits / (out.rows * out.columns))
    return invalid_argument(seg + " claims NumberOfFrames " + frames_text + " of Rows " + std::to_string(rows) +
                            " x Columns " + std::to_string(columns) + ", more pixels than a Pixel Data can hold");
  out.frames = frames;

  SOIQ_RETURN_IF_ERROR(decompress_pixels(ds, path));
  DcmElement* element = nullptr;
  if (ds.findAndGetElement(DCM_PixelData, element).bad() || element == nullptr)
    return invalid_argument(seg + " has no Pixel Data");
  const size_t length = element->getLength();
  if (length > 0 && element->getTag().getEVR() == EVR_OW) {
    // DCMTK keeps OW words in host byte order; the bit stream is their little-endian bytes.
    Uint16* words = nullptr;
    if (element->getUint16Array(words).bad() || words == nullptr)
      return invalid_argument(seg + ": its Pixel Data (OW) cannot be read");
    out.words_as_bytes.resize(length / 2 * 2);
    for (size_t n = 0; n < length / 2; ++n) {
      out.words_as_bytes[2 * n] = static_cast<uint8_t>(words[n] & 0xFF);
      out.words_as_bytes[2 * n + 1] = static_cast<uint8_t>(words[n] >> 8);
    }
    out.bytes = out.words_as_bytes;
  } else if (length > 0) {
    Uint8* bytes = nullptr;
    if (element->getUint8Array(bytes).bad() || bytes == nullptr)
      return invalid_argument(seg + ": its Pixel Data cannot be read");
    out.bytes = std::span<const uint8_t>(bytes, length);
  }
  const int64_t needed = binary_pixel_data_bytes(out.rows, out.columns, out.frames);
  if (static_cast<int64_t>(out.bytes.size()) < needed)
    return invalid_argument(seg + " is truncated: " + std::to_string(out.bytes.size()) +
                            " bytes of pixel data, NumberOfFrames " + frames_text + " x Rows " + std::to_string(rows) +
                            " x Columns " + std::to_string(columns) + " needs " + std::to_string(needed));
  return out;
}

Result<int64_t> slice_of_frame(FGInterface& fg, size_t f, const ImageGeometry& grid) {
  const auto frame_no = static_cast<Uint32>(f);
  auto* orientation = dynamic_cast<FGPlaneOrientationPatient*>(fg.get(frame_no, DcmFGTypes::EFG_PLANEORIENTPATIENT));
  auto* position = dynamic_cast<FGPlanePosPatient*>(fg.get(frame_no, DcmFGTypes::EFG_PLANEPOSPATIENT));
  Float64 o[6] = {};
  Float64 p[3] = {};
  if (!orientation || orientation->getImageOrientationPatient(o[0], o[1], o[2], o[3], o[4], o[5]).bad())
    return invalid_argument(frame_name(f) + " has no Plane Orientation (Patient)");
  if (!position || position->getImagePositionPatient(p[0], p[1], p[2]).bad())
    return invalid_argument(frame_name(f) + " has no Plane Position (Patient)");
  for (int axis = 0; axis < 2; ++axis) {
    double diff = 0;
    for (int r = 0; r < 3; ++r) diff = std::max(diff, std::abs(o[3 * axis + r] - grid.direction[r][axis]));
    if (diff > kOrientationTolerance)
      return invalid_argument(frame_name(f) + ": its " + (axis == 0 ? "row" : "column") + " direction " +
                              vec_text(o[3 * axis], o[3 * axis + 1], o[3 * axis + 2]) + " differs from the grid's " +
                              vec_text(grid.direction[0][axis], grid.direction[1][axis], grid.direction[2][axis]));
  }
  if (auto* measures = dynamic_cast<FGPixelMeasures*>(fg.get(frame_no, DcmFGTypes::EFG_PIXELMEASURES))) {
    Float64 between_rows = 0, between_columns = 0;
    if (measures->getPixelSpacing(between_rows, 0).good() && measures->getPixelSpacing(between_columns, 1).good()) {
      const double expected[2] = {grid.spacing_mm[1], grid.spacing_mm[0]};
      const double got[2] = {between_rows, between_columns};
      for (int a = 0; a < 2; ++a)
        if (std::abs(got[a] - expected[a]) > kSpacingRelativeTolerance * expected[a])
          return invalid_argument(frame_name(f) + ": Pixel Spacing " + std::to_string(got[0]) + "\\" +
                                  std::to_string(got[1]) + " mm differs from the grid's " +
                                  std::to_string(expected[0]) + "\\" + std::to_string(expected[1]));
    }
  }
  const Vec3 ijk = grid.physical_to_index({p[0], p[1], p[2]});
  const double k = std::round(ijk[2]);
  const double off[3] = {ijk[0] * grid.spacing_mm[0], ijk[1] * grid.spacing_mm[1], (ijk[2] - k) * grid.spacing_mm[2]};
  bool on_plane = k >= 0 && k < static_cast<double>(grid.dims[2]);
  for (int a = 0; a < 3; ++a) on_plane = on_plane && std::abs(off[a]) <= position_tolerance_mm(grid.spacing_mm[a]);
  if (!on_plane)
    return invalid_argument(frame_name(f) + ": its Plane Position " + vec_text(p[0], p[1], p[2]) +
                            " mm is at continuous index " + vec_text(ijk[0], ijk[1], ijk[2]) +
                            ", not on a slice (0, 0, k) of the grid (" + describe(grid) + ")");
  return static_cast<int64_t>(k);
}

std::string frame_source_uid(FGInterface& fg, size_t f) {
  auto* derived = dynamic_cast<FGDerivationImage*>(fg.get(static_cast<Uint32>(f), DcmFGTypes::EFG_DERIVATIONIMAGE));
  if (!derived) return "";
  for (DerivationImageItem* item : derived->getDerivationImageItems())
    for (SourceImageItem* source : item->getSourceImageItems()) {
      OFString uid;
      if (source->getImageSOPInstanceReference().getReferencedSOPInstanceUID(uid).good() && !uid.empty())
        return uid.c_str();
    }
  return "";
}

Result<RunLengthVolume> segment_volume(const BinaryPixels& pixels, const std::vector<FrameOnGrid>& frames,
                                       const ImageGeometry& grid) {
  const int64_t nx = grid.dims[0], ny = grid.dims[1];
  RunLengthVolume v = empty_volume(grid);
  v.line_start.assign(1, 0);
  std::vector<uint8_t> slice(static_cast<size_t>(nx * ny));
  size_t next = 0;
  for (int64_t k = 0; k < grid.dims[2]; ++k) {
    if (next == frames.size() || frames[next].k != k) {
      v.line_start.insert(v.line_start.end(), static_cast<size_t>(ny), static_cast<int64_t>(v.runs.size()));
      continue;
    }
    std::fill(slice.begin(), slice.end(), uint8_t{0});
    for (; next < frames.size() && frames[next].k == k; ++next) {
      SOIQ_ASSIGN_OR_RETURN(const std::vector<uint8_t> frame,
                            unpack_binary_frame(pixels.bytes, pixels.rows, pixels.columns, pixels.frames,
                                                static_cast<int64_t>(frames[next].frame)));
      for (size_t n = 0; n < slice.size(); ++n) slice[n] |= frame[n];
    }
    for (int64_t j = 0; j < ny; ++j) {
      const uint8_t* row = slice.data() + j * nx;
      for (int64_t i = 0; i < nx;) {
        if (!row[i]) {
          ++i;
          continue;
        }
        const int64_t begin = i;
        while (i < nx && row[i]) ++i;
        v.runs.push_back({static_cast<int32_t>(begin), static_cast<int32_t>(i)});
      }
      v.line_start.push_back(static_cast<int64_t>(v.runs.size()));
    }
  }
  return v;
}

}  // namespace soiq::dicom
