#include "dicom/read_seg.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmfg/fgseg.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <memory>
#include <mutex>

#include "dicom/dcmtk_file.h"
#include "dicom/read_seg_frames.h"

namespace soiq::dicom {
namespace {

// DCMTK 3.6.7's SEG reader unpacks the frames itself with each one starting on a byte, which misreads
// standard files (PS3.5 8.1.1 / 8.2: frames are back to back; see seg_bit_packing.h) and walks
// past a short Pixel Data. Everything but the Pixel Data is read through it; the pixels are ours.
class SegWithoutPixelData : public DcmSegmentation {
 public:
  OFCondition read_without_pixel_data(DcmItem& ds) { return readWithoutPixelData(ds); }
};

std::string code_text(CodeSequenceMacro& code) {
  OFString scheme, value;
  code.getCodingSchemeDesignator(scheme);
  code.getCodeValue(value);
  return std::string(scheme.c_str()) + ":" + value.c_str();
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

// Maps every frame to its segment and its slice of `grid`, recording each frame's source in
// out.segments (already one per segment); returns the frames of each segment in file order.
// `name` and `seg_name` name the object in messages.
Result<std::vector<std::vector<FrameOnGrid>>> place_frames(SegWithoutPixelData& seg, const BinaryPixels& pixels,
                                                           const ImageGeometry& grid, const std::string& name,
                                                           const std::string& seg_name, SegObject& out) {
  const size_t segment_count = out.segments.size();
  std::vector<std::vector<FrameOnGrid>> frames_of(segment_count);
  FGInterface& fg = seg.getFunctionalGroups();
  const size_t frame_count = seg.getNumberOfFrames();  // Per-Frame Functional Groups items
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
    out.segments[number - 1].frames.push_back({*k, frame_source_uid(fg, f)});
  }
  return frames_of;
}

// Segment n's number, label, algorithm and codes from its Segment Sequence item.
void read_segment_description(DcmSegment& s, size_t n, ReadSegment& r) {
  r.segment_number = static_cast<int32_t>(n + 1);
  OFString text;
  if (s.getSegmentLabel(text).good()) r.label = text.c_str();
  r.algorithm_type = DcmSegTypes::algoType2OFString(s.getSegmentAlgorithmType()).c_str();
  if (s.getSegmentAlgorithmName(text).good()) r.algorithm_name = text.c_str();
  r.category_code = code_text(s.getSegmentedPropertyCategoryCode());
  r.type_code = code_text(s.getSegmentedPropertyTypeCode());
}

// Without a Referenced Series Sequence, the references are the frames' sources, each once, in
// file order.
void references_from_sources(SegObject& out) {
  for (const ReadSegment& r : out.segments)
    for (const SegFrameSource& f : r.frames)
      if (!f.source_sop_instance_uid.empty() &&
          std::find(out.referenced_sop_instance_uids.begin(), out.referenced_sop_instance_uids.end(),
                    f.source_sop_instance_uid) == out.referenced_sop_instance_uids.end())
        out.referenced_sop_instance_uids.push_back(f.source_sop_instance_uid);
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

  out.segments.resize(seg->getNumberOfSegments());
  SOIQ_ASSIGN_OR_RETURN(std::vector<std::vector<FrameOnGrid>> frames_of,
                        place_frames(*seg, pixels, grid, name, seg_name, out));
  for (size_t n = 0; n < out.segments.size(); ++n) {
    DcmSegment* s = seg->getSegment(n + 1);
    if (!s) return data_loss(name + ": segment " + std::to_string(n + 1) + " is missing");
    read_segment_description(*s, n, out.segments[n]);
    auto& frames = frames_of[n];
    std::stable_sort(frames.begin(), frames.end(), [](const auto& a, const auto& b) { return a.k < b.k; });
    SOIQ_ASSIGN_OR_RETURN(out.segments[n].volume, segment_volume(pixels, frames, grid));
  }
  if (out.referenced_sop_instance_uids.empty()) references_from_sources(out);
  return out;
}

}  // namespace

Result<SegObject> read_seg_file(const std::string& path, const ImageGeometry& grid) {
  SOIQ_ASSIGN_OR_RETURN(auto file, load_dicom_file(path, /*until_pixel_data=*/false));
  return read_dataset(*file->getDataset(), path, grid);
}

}  // namespace soiq::dicom
