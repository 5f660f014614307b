#include "dicom/read_seg.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmfg/fgseg.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <span>

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

struct FrameOnGrid {
  size_t frame = 0;  // DCMTK's frame index, from 0
  int64_t k = 0;
};

std::string frame_name(size_t f) { return "SEG frame " + std::to_string(f + 1); }

// The most pixels a Pixel Data value can hold at one bit each: its length field is 32 bits (even).
constexpr int64_t kMaxPixelDataBits = 8 * 0xFFFFFFFELL;

// DCMTK 3.6.7's SEG reader unpacks the frames itself with each one starting on a byte, which misreads
// standard files (PS3.5 8.1.1 / 8.2: frames are back to back; see seg_bit_packing.h) and walks
// past a short Pixel Data. Everything but the Pixel Data is read through it; the pixels are ours.
class SegWithoutPixelData : public DcmSegmentation {
 public:
  OFCondition read_without_pixel_data(DcmItem& ds) { return readWithoutPixelData(ds); }
};

// The Pixel Data of a binary SEG, checked against what its header claims before anything is read.
struct BinaryPixels {
  int64_t rows = 0, columns = 0, frames = 0;
  std::vector<uint8_t> words_as_bytes;  // the bytes of an OW value, little-endian as in the file
  std::span<const uint8_t> bytes;       // the whole Pixel Data value
};

// `path` only names the object in messages, as `seg` does ("SEG '<path>'").
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

std::string vec_text(double x, double y, double z) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
}

// Slice k of `grid` that frame f lies on, or INVALID_ARGUMENT saying what does not fit.
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

std::string code_text(CodeSequenceMacro& code) {
  OFString scheme, value;
  code.getCodingSchemeDesignator(scheme);
  code.getCodeValue(value);
  return std::string(scheme.c_str()) + ":" + value.c_str();
}

std::string source_uid(FGInterface& fg, size_t f) {
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

// Runs of one segment from its frames (sorted by k): slice by slice, frames on one slice united.
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

void read_references(DcmDataset& ds, SegObject& out) {
  DcmItem* series = nullptr;
  if (ds.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).bad() || !series) return;
  out.referenced_series_uid = get_string(*series, DCM_SeriesInstanceUID);
  DcmSequenceOfItems* instances = nullptr;
  if (series->findAndGetSequence(DCM_ReferencedInstanceSequence, instances).bad() || !instances) return;
  for (unsigned long n = 0; n < instances->card(); ++n)
    out.referenced_sop_instance_uids.push_back(get_string(*instances->getItem(n), DCM_ReferencedSOPInstanceUID));
}

Result<SegObject> read_dataset(DcmDataset& ds, const std::string& path, const ImageGeometry& grid) {
  const std::string name = "'" + path + "'";
  const std::string seg_name = "SEG '" + path + "'";
  SOIQ_RETURN_IF_ERROR(validate_geometry(grid));
  const std::string sop_class = get_string(ds, DCM_SOPClassUID);
  if (sop_class != UID_SegmentationStorage)
    return invalid_argument(name + " is not a DICOM Segmentation (SOP class '" + sop_class + "', modality '" +
                            get_string(ds, DCM_Modality) + "')");
  static std::once_flag quiet;  // DCMTK's IOD readers log to stderr; problems come back as a Status
  std::call_once(quiet, [] {
    for (OFLogger* log : {&DCM_dcmsegLogger, &DCM_dcmfgLogger, &DCM_dcmiodLogger})
      log->setLogLevel(OFLogger::FATAL_LOG_LEVEL);
  });
  // The header and the Pixel Data length are checked before DCMTK reads anything else.
  SOIQ_ASSIGN_OR_RETURN(const BinaryPixels pixels, binary_pixels(ds, path, seg_name));
  if (pixels.rows != grid.dims[1] || pixels.columns != grid.dims[0])
    return invalid_argument(name + " has frames of " + std::to_string(pixels.rows) + " rows x " +
                            std::to_string(pixels.columns) + " columns; the grid (" + describe(grid) + ") needs " +
                            std::to_string(grid.dims[1]) + " x " + std::to_string(grid.dims[0]));
  auto seg = std::make_unique<SegWithoutPixelData>();
  const OFCondition c = seg->read_without_pixel_data(ds);
  if (c.bad()) return condition_status(StatusCode::kDataLoss, path, "not a readable DICOM Segmentation", c);

  SegObject out;
  out.sop_instance_uid = get_string(ds, DCM_SOPInstanceUID);
  out.series_uid = get_string(ds, DCM_SeriesInstanceUID);
  out.study_uid = get_string(ds, DCM_StudyInstanceUID);
  out.patient_id = get_string(ds, DCM_PatientID);
  out.frame_of_reference_uid = get_string(ds, DCM_FrameOfReferenceUID);
  read_references(ds, out);

  const size_t segment_count = seg->getNumberOfSegments();
  std::vector<std::vector<FrameOnGrid>> frames_of(segment_count);
  out.segments.resize(segment_count);
  FGInterface& fg = seg->getFunctionalGroups();
  const size_t frame_count = seg->getNumberOfFrames();  // Per-Frame Functional Groups items
  if (static_cast<int64_t>(frame_count) != pixels.frames)
    return invalid_argument(seg_name + " has " + std::to_string(frame_count) +
                            " Per-Frame Functional Groups items but NumberOfFrames " + std::to_string(pixels.frames));
  for (size_t f = 0; f < frame_count; ++f) {
    auto* s = dynamic_cast<FGSegmentation*>(fg.get(static_cast<Uint32>(f), DcmFGTypes::EFG_SEGMENTATION));
    Uint16 number = 0;
    if (!s || s->getReferencedSegmentNumber(number).bad() || number < 1 || number > segment_count)
      return invalid_argument(name + ": " + frame_name(f) + " has no valid Referenced Segment Number (" +
                              std::to_string(number) + " of " + std::to_string(segment_count) + " segments)");
    auto k = slice_of_frame(fg, f, grid);
    if (!k.ok()) return Status(k.status().code(), name + ": " + k.status().message());
    frames_of[number - 1].push_back({f, *k});
    out.segments[number - 1].frames.push_back({*k, source_uid(fg, f)});
  }
  for (size_t n = 0; n < segment_count; ++n) {
    ReadSegment& r = out.segments[n];
    DcmSegment* s = seg->getSegment(n + 1);
    if (!s) return data_loss(name + ": segment " + std::to_string(n + 1) + " is missing");
    r.segment_number = static_cast<int32_t>(n + 1);
    OFString text;
    if (s->getSegmentLabel(text).good()) r.label = text.c_str();
    r.algorithm_type = DcmSegTypes::algoType2OFString(s->getSegmentAlgorithmType()).c_str();
    if (s->getSegmentAlgorithmName(text).good()) r.algorithm_name = text.c_str();
    r.category_code = code_text(s->getSegmentedPropertyCategoryCode());
    r.type_code = code_text(s->getSegmentedPropertyTypeCode());
    auto& frames = frames_of[n];
    std::stable_sort(frames.begin(), frames.end(), [](const auto& a, const auto& b) { return a.k < b.k; });
    SOIQ_ASSIGN_OR_RETURN(r.volume, segment_volume(pixels, frames, grid));
  }
  if (out.referenced_sop_instance_uids.empty())  // no Referenced Series Sequence: the frames' sources
    for (const ReadSegment& r : out.segments)
      for (const SegFrameSource& f : r.frames)
        if (!f.source_sop_instance_uid.empty() &&
            std::find(out.referenced_sop_instance_uids.begin(), out.referenced_sop_instance_uids.end(),
                      f.source_sop_instance_uid) == out.referenced_sop_instance_uids.end())
          out.referenced_sop_instance_uids.push_back(f.source_sop_instance_uid);
  return out;
}

}  // namespace

Result<SegObject> read_seg_file(const std::string& path, const ImageGeometry& grid) {
  SOIQ_ASSIGN_OR_RETURN(auto file, load_dicom_file(path, /*until_pixel_data=*/false));
  return read_dataset(*file->getDataset(), path, grid);
}

}  // namespace soiq::dicom
