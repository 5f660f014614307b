#include "dicom/seg_export.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmseg/segdoc.h>

#include <algorithm>
#include <memory>
#include <mutex>

#include "dicom/dcmtk_file.h"
#include "dicom/seg_export_steps.h"

namespace soiq::dicom {
namespace {

// Pixel Data has a 32-bit length (even, so 0xFFFFFFFE at most).
constexpr int64_t kMaxPixelDataBytes = 0xFFFFFFFELL;

Status validate(const SegSource& source, const std::vector<SegSegment>& segments, const SegWriteOptions& options,
                std::vector<std::vector<int64_t>>& slices_of_segment) {
  SOIQ_RETURN_IF_ERROR(check_seg_source(source));
  if (segments.empty()) return invalid_argument("no segments to write");
  if (segments.size() > 65535) return invalid_argument("a SEG holds at most 65535 segments");

  int64_t frames = 0;
  slices_of_segment.clear();
  for (size_t s = 0; s < segments.size(); ++s) {
    const SegSegment& seg = segments[s];
    SOIQ_RETURN_IF_ERROR(check_segment(seg, s + 1, seg.volume.geometry, source.geometry));
    if (static_cast<int64_t>(seg.volume.line_start.size()) != seg.volume.line_count() + 1)
      return invalid_argument("segment " + std::to_string(s + 1) + " ('" + seg.label +
                              "'): malformed run-length volume (line_start has " +
                              std::to_string(seg.volume.line_start.size()) + " entries)");
    slices_of_segment.push_back(occupied_slices(seg.volume));
    if (slices_of_segment.back().empty()) return invalid_argument("structure '" + seg.label + "' has no voxels");
    frames += static_cast<int64_t>(slices_of_segment.back().size());
  }
  const int64_t bits = frames * source.geometry.dims[0] * source.geometry.dims[1];
  return check_seg_size(frames, (bits + 7) / 8, options);
}

bool beyond_ascii(const std::string& v) {
  return std::any_of(v.begin(), v.end(), [](char ch) { return static_cast<unsigned char>(ch) >= 0x80; });
}

}  // namespace

Status seg_export_error(const std::string& what, const OFCondition& cond) {
  return internal_error("DICOM SEG: " + what + " (" + cond.text() + ")");
}

std::string new_uid(const char* root) {
  char buf[100];
  dcmGenerateUniqueIdentifier(buf, root);
  return buf;
}

Status check_seg_source(const SegSource& source) {
  const ImageGeometry& g = source.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  if (g.dims[0] < 1 || g.dims[1] < 1 || g.dims[0] > 65535 || g.dims[1] > 65535)
    return invalid_argument("source series grid is " + describe(g) + "; a SEG frame needs 1 to 65535 rows and columns");
  if (static_cast<int64_t>(source.slice_sop_instance_uids.size()) != g.dims[2])
    return invalid_argument("source series has " + std::to_string(source.slice_sop_instance_uids.size()) +
                            " slice SOP instance uids but its grid has " + std::to_string(g.dims[2]) + " slices");
  for (size_t k = 0; k < source.slice_sop_instance_uids.size(); ++k)
    if (source.slice_sop_instance_uids[k].empty())
      return invalid_argument("source series: slice " + std::to_string(k) + " has no SOP instance uid");
  const std::pair<const char*, const std::string*> required[] = {
      {"study uid", &source.study_uid},
      {"series uid", &source.series_uid},
      {"frame of reference uid", &source.frame_of_reference_uid},
      {"SOP class uid", &source.sop_class_uid}};
  for (const auto& [name, value] : required)
    if (value->empty()) return invalid_argument(std::string("source series has no ") + name);
  return ok_status();
}

Status check_segment(const SegSegmentDescription& s, size_t number, const ImageGeometry& volume_grid,
                     const ImageGeometry& source_grid) {
  const std::string name = "segment " + std::to_string(number) + " ('" + s.label + "')";
  if (s.label.empty()) return invalid_argument("segment " + std::to_string(number) + " has an empty label");
  if (s.algorithm_type != SegAlgorithmType::kManual && s.algorithm_name.empty())
    return invalid_argument(name + " needs an algorithm name unless its algorithm type is MANUAL");
  const Status same = check_same_grid(volume_grid, source_grid);
  if (!same.ok())
    return invalid_argument(name + " is not on the source series grid (" + describe(source_grid) +
                            "): " + same.message());
  return ok_status();
}

Status check_seg_size(int64_t frames, int64_t pixel_data_bytes, const SegWriteOptions& options) {
  if (frames > options.max_frames)
    return resource_exhausted("the SEG would have " + std::to_string(frames) + " frames, over the limit of " +
                              std::to_string(options.max_frames) + "; write fewer segments per object");
  if (pixel_data_bytes > kMaxPixelDataBytes)
    return resource_exhausted("the SEG would have " + std::to_string(pixel_data_bytes) +
                              " bytes of pixel data, over DICOM's 32-bit limit; write fewer segments per object");
  return ok_status();
}

void quiet_dcmtk_seg_logs() {
  static std::once_flag quiet;
  std::call_once(quiet, [] {
    for (OFLogger* log : {&DCM_dcmsegLogger, &DCM_dcmfgLogger, &DCM_dcmiodLogger})
      log->setLogLevel(OFLogger::FATAL_LOG_LEVEL);
  });
}

Result<std::unique_ptr<DcmSegmentation>> create_seg(const SegSource& source, const SegWriteOptions& options,
                                                    Uint16 max_fractional_value) {
  DcmSegmentation* raw = nullptr;
  const IODGeneralEquipmentModule::EquipmentInfo equipment("soiq", "soiq", "1", "soiq");
  const ContentIdentificationMacro content("1", options.content_label.c_str(), options.content_description.c_str(), "");
  const Uint16 rows = static_cast<Uint16>(source.geometry.dims[1]),
               columns = static_cast<Uint16>(source.geometry.dims[0]);
  const OFCondition c =
      max_fractional_value == 0
          ? DcmSegmentation::createBinarySegmentation(raw, rows, columns, equipment, content)
          : DcmSegmentation::createFractionalSegmentation(raw, rows, columns, DcmSegTypes::SFT_OCCUPANCY,
                                                          max_fractional_value, equipment, content);
  std::unique_ptr<DcmSegmentation> seg(raw);
  if (c.bad() || !seg) return invalid_argument("DICOM SEG: cannot create it (" + std::string(c.text()) + ")");
  return seg;
}

Status describe_seg(DcmSegmentation& seg, const SegSource& source,
                    const std::vector<const SegSegmentDescription*>& segments, const SegWriteOptions& options,
                    WrittenSeg& out) {
  out.series_uid = options.series_uid.empty() ? new_uid(SITE_SERIES_UID_ROOT) : options.series_uid;
  out.sop_instance_uid = options.sop_instance_uid.empty() ? new_uid(SITE_INSTANCE_UID_ROOT) : options.sop_instance_uid;
  SOIQ_RETURN_IF_ERROR(set_identity(seg, source, options, out.series_uid, out.sop_instance_uid));
  for (const SegSegmentDescription* s : segments) SOIQ_RETURN_IF_ERROR(add_segment(seg, *s));
  return add_shared_groups(seg, source.geometry, options.dimension_organization_uid);
}

Status encode_seg(DcmSegmentation& seg, const SegSource& source,
                  const std::vector<const SegSegmentDescription*>& segments, const SegWriteOptions& options,
                  const BinaryFramePacker* pixels, WrittenSeg& out) {
  out.frame_count = static_cast<int64_t>(seg.getNumberOfFrames());
  DcmFileFormat file;
  const OFCondition c = seg.writeDataset(*file.getDataset());
  if (c.bad()) return seg_export_error("DCMTK refused the object", c);
  // A patient's name, segment label or description beyond ASCII is UTF-8 (the store keeps text so):
  // declared, or readers would take its bytes for ISO 646.
  bool utf8 = beyond_ascii(source.patient_name) || beyond_ascii(options.series_description);
  for (const SegSegmentDescription* s : segments) utf8 = utf8 || beyond_ascii(s->label);
  if (utf8 && file.getDataset()->putAndInsertString(DCM_SpecificCharacterSet, "ISO_IR 192").bad())
    return internal_error("DICOM SEG: Specific Character Set could not be set");
  if (!options.content_date.empty() &&
      (file.getDataset()->putAndInsertString(DCM_ContentDate, options.content_date.c_str()).bad() ||
       file.getDataset()->putAndInsertString(DCM_ContentTime, options.content_time.c_str()).bad()))
    return invalid_argument("DICOM SEG: content date '" + options.content_date + "' or time '" + options.content_time +
                            "' was refused");
  if (pixels != nullptr) SOIQ_RETURN_IF_ERROR(put_pixel_data(*file.getDataset(), *pixels));
  Result<std::string> bytes = part10_bytes(file);
  if (!bytes.ok()) return Status(bytes.status().code(), "DICOM SEG: " + bytes.status().message());
  out.bytes = std::move(*bytes);
  return ok_status();
}

Result<WrittenSeg> write_seg(const SegSource& source, const std::vector<SegSegment>& segments,
                             const SegWriteOptions& options) {
  std::vector<std::vector<int64_t>> slices;
  SOIQ_RETURN_IF_ERROR(validate(source, segments, options, slices));
  quiet_dcmtk_seg_logs();

  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<DcmSegmentation> seg, create_seg(source, options, 0));
  std::vector<const SegSegmentDescription*> described;
  for (const SegSegment& s : segments) described.push_back(&s);
  WrittenSeg out;
  SOIQ_RETURN_IF_ERROR(describe_seg(*seg, source, described, options, out));
  BinaryFramePacker pixels;
  for (size_t s = 0; s < segments.size(); ++s)
    SOIQ_RETURN_IF_ERROR(add_frames(*seg, source, segments[s], static_cast<Uint16>(s + 1), slices[s], pixels));
  SOIQ_RETURN_IF_ERROR(add_references(*seg, source, slices));
  SOIQ_RETURN_IF_ERROR(encode_seg(*seg, source, described, options, &pixels, out));
  return out;
}

int64_t seg_write_peak_bytes(const ImageGeometry& geometry, const std::vector<SegSegment>& segments) {
  int64_t frames = 0;
  for (const SegSegment& s : segments) {
    if (static_cast<int64_t>(s.volume.line_start.size()) != s.volume.line_count() + 1) continue;
    frames += static_cast<int64_t>(occupied_slices(s.volume).size());
  }
  const int64_t frame_pixels = geometry.dims[0] * geometry.dims[1];
  return 3 * ((frames * frame_pixels + 7) / 8) + frame_pixels + frames * 4096 + (int64_t(1) << 20);
}

}  // namespace soiq::dicom
