#include "server/app/structure_rt_struct.h"

#include <array>

#include "core/geometry/slice_sections.h"
#include "server/app/structures_on_series.h"

namespace soiq::server {
namespace rt_struct_building {

// The colours soiq's SEGs give their segments (structure_seg.cpp), so one structure looks the same
// in either object.
constexpr std::array<std::array<uint8_t, 3>, 6> kPalette = {
    {{255, 64, 64}, {64, 160, 255}, {80, 200, 80}, {255, 200, 0}, {200, 80, 255}, {0, 200, 200}}};

// Bytes the writing holds per contour point: the point (24), its text in the dataset and again
// in the Part 10 bytes (3 DS values of up to 17 bytes each, twice).
constexpr int64_t kBytesPerPoint = 24 + 2 * 3 * 17;

// LO: at most 64 characters, no backslash or control characters.
Status check_series_description(const std::string& d) {
  bool ok = d.size() <= 64;
  for (char c : d) ok = ok && c != '\\' && static_cast<unsigned char>(c) >= 0x20;
  if (ok) return ok_status();
  return invalid_argument("series description '" + d +
                          "' is not a DICOM LO value: at most 64 characters, no backslash or control characters");
}

// An ROI Name is LO too: a structure named otherwise keeps its name where it fits.
std::string roi_name(const db::StructureRecord& s) {
  std::string out;
  for (char c : s.name)
    if (c != '\\' && static_cast<unsigned char>(c) >= 0x20) out += c;
  if (out.size() > 64) out.resize(64);
  return out.empty() ? "structure " + std::to_string(s.id) : out;
}

}  // namespace rt_struct_building

std::string rt_struct_series_description(const std::string& name) {
  return rt_struct_building::check_series_description(name).ok() && !name.empty()
             ? name
             : dicom::RtStructWriteOptions{}.series_description;
}

Result<BudgetedRtStruct> structure_rt_struct(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                             const std::vector<int64_t>& ids, const std::string& series_description,
                                             const StructureObjectUids* uids, const std::function<Status()>& stop) {
  namespace b = rt_struct_building;
  SOIQ_RETURN_IF_ERROR(b::check_series_description(series_description));
  SOIQ_ASSIGN_OR_RETURN(const StructuresOnSeries on,
                        structures_on_series(store, ids, kMaxRtStructStructures, "RT Structure Set"));
  std::vector<dicom::RtStructRoi> rois;
  int64_t points = 0;
  for (const db::StructureRecord& s : on.structures) {
    SOIQ_ASSIGN_OR_RETURN(const std::shared_ptr<const TriangleMesh> surface, features.surface(s));
    dicom::RtStructRoi roi;
    roi.name = b::roi_name(s);
    roi.display_rgb = b::kPalette[rois.size() % b::kPalette.size()];
    SOIQ_ASSIGN_OR_RETURN(roi.contours, slice_sections(*surface, on.source.geometry, s.name));
    for (const SliceSection& c : roi.contours) points += int64_t(c.points_mm.size());
    rois.push_back(std::move(roi));
  }
  SOIQ_ASSIGN_OR_RETURN(MemoryBudget::Reservation writing,
                        budget.reserve(points * b::kBytesPerPoint + (int64_t(1) << 20),
                                       "writing the RT Structure Set of " + structure_named(on.structures.front()),
                                       stop, "export fewer structures at once, or raise the budget"));
  dicom::RtStructWriteOptions options;
  if (!series_description.empty()) options.series_description = series_description;
  if (uids != nullptr) {
    // The same structure's RT Structure Set is the same object every time it is written: same
    // UIDs, and the date and time of the structure, not of the request.
    options.series_uid = uids->series_uid;
    options.sop_instance_uid = uids->sop_instance_uid;
    const std::string& at = on.structures.front().created_at;  // 2026-11-27T03:02:54.642Z
    if (at.size() >= 19) {
      options.date = at.substr(0, 4) + at.substr(5, 2) + at.substr(8, 2);
      options.time = at.substr(11, 2) + at.substr(14, 2) + at.substr(17, 2);
    }
  }
  SOIQ_ASSIGN_OR_RETURN(dicom::WrittenRtStruct written, dicom::write_rt_struct(on.source, rois, options));
  writing.shrink_to(int64_t(written.bytes.capacity()));
  return BudgetedRtStruct{std::move(written), on.source.series_uid, on.source.study_uid, std::move(writing)};
}

}  // namespace soiq::server
