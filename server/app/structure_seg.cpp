#include "server/app/structure_seg.h"

#include <array>
#include <set>

#include "core/base/coverage_volume.h"
#include "core/base/image_geometry.h"
#include "core/voxelize/coverage_1d.h"
#include "dicom/seg_export_fractional.h"

namespace soiq::server {
namespace {

// How long a reservation waits while this SEG holds others' bytes (memory_budget.h).
constexpr int kHoldingPatienceMs = 30000;

std::string named(const db::StructureRecord& s) { return "structure " + std::to_string(s.id) + " ('" + s.name + "')"; }

Result<std::vector<db::StructureRecord>> structures_of_one_series(db::Store& store, const std::vector<int64_t>& ids,
                                                                  bool fractional) {
  if (ids.empty()) return invalid_argument("no structure ids given: name the structures to put in the SEG");
  if (ids.size() > size_t(kMaxSegStructures))
    return invalid_argument(std::to_string(ids.size()) + " structures asked; one SEG holds at most " +
                            std::to_string(kMaxSegStructures));
  std::set<int64_t> seen;
  std::vector<db::StructureRecord> out;
  for (int64_t id : ids) {
    if (!seen.insert(id).second) return invalid_argument("structure " + std::to_string(id) + " is named twice");
    SOIQ_ASSIGN_OR_RETURN(db::StructureRecord s, store.get_structure(id));
    // Before the missing DICOM source: that a fractional SEG can never hold it is the deeper reason.
    if (fractional && s.robust)
      return failed_precondition(named(s) +
                                 " was uploaded in robust mode (its surface is open or self-intersecting): coverage "
                                 "fractions need a closed surface, so it has no fractional SEG; export a binary SEG");
    if (s.source_series_uid.empty())
      return failed_precondition(named(s) +
                                 " was uploaded as a surface, not imported from DICOM, so there are no DICOM images "
                                 "for a SEG to reference; import the images and the RT Structure Set with 'soiq "
                                 "import' and export that structure");
    if (!out.empty() && s.source_series_uid != out.front().source_series_uid)
      return failed_precondition(named(out.front()) + " is on series " + out.front().source_series_uid + " but " +
                                 named(s) + " is on series " + s.source_series_uid +
                                 "; one SEG references one series: export them separately");
    out.push_back(std::move(s));
  }
  return out;
}

// Series Description is a DICOM LO: at most 64 characters, no backslash or control characters.
Status check_series_description(const std::string& d) {
  bool ok = d.size() <= 64;
  for (char c : d) ok = ok && c != '\\' && static_cast<unsigned char>(c) >= 0x20;
  if (ok) return ok_status();
  return invalid_argument("series description '" + d +
                          "' is not a DICOM LO value: at most 64 characters, no backslash or control characters");
}

dicom::SegSource seg_source(const db::PatientRecord& patient, const db::StudyRecord& study,
                            const db::SeriesRecord& series) {
  dicom::SegSource source;
  source.patient_id = patient.patient_id;
  source.patient_name = patient.patient_name;  // "" unless soiqd keeps names
  source.patient_sex = patient.sex;
  source.patient_birth_date = patient.birth_date;
  source.study_uid = study.study_uid;
  source.study_date = study.study_date;
  source.study_time = study.study_time;
  source.study_id = study.study_id;
  source.accession_number = study.accession_number;
  source.series_uid = series.series_uid;
  source.frame_of_reference_uid = series.frame_of_reference_uid;
  source.modality = series.modality;
  source.sop_class_uid = series.sop_class_uid;
  source.slice_sop_instance_uids = series.slice_instance_uids;
  source.geometry = series.geometry;
  return source;
}

// Segment `index` (from 0) labelled with the structure's name, with a colour as soiq's pictures
// draw the first (render/overlay_picture.h): without one, viewers pick their own and say so over
// the image (OHIF).
dicom::SegSegmentDescription describe_segment(const db::StructureRecord& s, size_t index) {
  static constexpr std::array<std::array<uint8_t, 3>, 6> kPalette = {
      {{255, 64, 64}, {64, 160, 255}, {80, 200, 80}, {255, 200, 0}, {200, 80, 255}, {0, 200, 200}}};
  dicom::SegSegmentDescription d;
  d.label = s.name;
  d.display_rgb = kPalette[index % kPalette.size()];
  return d;
}

// How long a segment's admission waits while the earlier segments of the SEG hold their voxels.
std::function<Status()> patient_stop(const std::function<Status()>& stop,
                                     const std::vector<FeatureEngine::Admission>& admitted) {
  return stop_when_held_too_long(
      stop, !admitted.empty(), kHoldingPatienceMs,
      "the structures of this SEG do not fit the memory budget together while other work holds it; export fewer "
      "structures at once, or raise the budget");
}

Result<MemoryBudget::Reservation> reserve_writing(MemoryBudget& budget, int64_t bytes, const std::string& what,
                                                  const std::function<Status()>& stop) {
  return budget.reserve(bytes, what,
                        stop_when_held_too_long(stop, true, kHoldingPatienceMs,
                                                "the SEG's writing does not fit the memory budget "
                                                "while other work holds it; export fewer structures "
                                                "at once, or raise the budget"),
                        "export fewer structures per SEG, or raise the budget");
}

}  // namespace

std::string seg_series_description(const std::string& name) {
  return check_series_description(name).ok() && !name.empty() ? name : dicom::SegWriteOptions{}.series_description;
}

Result<BudgetedSeg> structure_seg(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                  const std::vector<int64_t>& ids, const std::string& series_description,
                                  const StructureObjectUids* uids, const std::function<Status()>& stop,
                                  int oversample) {
  if (oversample < 0 || oversample > kMaxLinesPerVoxel)
    return invalid_argument("oversample must be 0 (a binary SEG) or 1 to " + std::to_string(kMaxLinesPerVoxel) +
                            " (a FRACTIONAL SEG of coverage fractions), not " + std::to_string(oversample));
  // Stable UIDs name a structure's binary SEG: a fractional one must never take them.
  if (oversample > 0 && uids != nullptr)
    return invalid_argument("a fractional SEG gets new UIDs: the stable ones name the binary SEG");
  SOIQ_RETURN_IF_ERROR(check_series_description(series_description));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::StructureRecord> structures,
                        structures_of_one_series(store, ids, oversample > 0));
  const std::string& series_uid = structures.front().source_series_uid;
  Result<db::SeriesRecord> series = store.get_series(series_uid);
  if (!series.ok() && series.status().code() == StatusCode::kNotFound)
    return not_found("the image series " + series_uid + " that " + named(structures.front()) +
                     " was converted on is no longer stored; import it again");
  SOIQ_RETURN_IF_ERROR(series.status());
  if (series->frame_of_reference_uid.empty() || series->sop_class_uid.empty() ||
      series->slice_instance_uids.size() != size_t(series->geometry.dims[2]))
    return failed_precondition("series " + series_uid +
                               " was stored without its DICOM references (frame of reference, slice SOP instances); "
                               "import its files again with 'soiq import' to export a SEG on it");
  SOIQ_RETURN_IF_ERROR(check_grid_size(series->geometry, features.max_grid_voxels()));
  SOIQ_ASSIGN_OR_RETURN(const db::StudyRecord study, store.get_study(series->study_uid));
  SOIQ_ASSIGN_OR_RETURN(const db::PatientRecord patient, store.get_patient(study.patient_id));
  const dicom::SegSource source = seg_source(patient, study, *series);

  dicom::SegWriteOptions options;
  if (!series_description.empty()) options.series_description = series_description;
  if (uids != nullptr) {
    // The same structure's SEG is the same object every time it is written: same UIDs, and the
    // date and time of the structure, not of the request.
    options.series_uid = uids->series_uid;
    options.sop_instance_uid = uids->sop_instance_uid;
    options.dimension_organization_uid = uids->sop_instance_uid + ".1";
    const std::string& at = structures.front().created_at;  // 2026-11-27T03:02:54.642Z
    if (at.size() >= 19) {
      options.content_date = at.substr(0, 4) + at.substr(5, 2) + at.substr(8, 2);
      options.content_time = at.substr(11, 2) + at.substr(14, 2) + at.substr(17, 2);
    }
  }
  const std::string what =
      "writing the SEG of " + named(structures.front()) +
      (structures.size() > 1 ? " and " + std::to_string(structures.size() - 1) + " more structures" : std::string());
  // Each segment's voxels stay admitted (`admitted`) until the SEG is written.
  std::vector<FeatureEngine::Admission> admitted;
  Result<dicom::WrittenSeg> written = internal_error("no SEG written");
  MemoryBudget::Reservation writing;
  if (oversample == 0) {
    std::vector<dicom::SegSegment> segments;
    for (const db::StructureRecord& s : structures) {
      SOIQ_ASSIGN_OR_RETURN(FeatureEngine::Admission a,
                            features.admit(s, series->geometry, {}, patient_stop(stop, admitted)));
      // Imported surfaces are closed and free of self-intersections: both fill rules agree.
      SOIQ_ASSIGN_OR_RETURN(Voxelization v, features.convert(a, s, series->geometry, FillRule::kNonZero));
      a.shrink_to(run_length_bytes(v.volume));
      admitted.push_back(std::move(a));
      dicom::SegSegment segment;
      static_cast<dicom::SegSegmentDescription&>(segment) = describe_segment(s, segments.size());
      segment.volume = std::move(v.volume);
      segments.push_back(std::move(segment));
    }
    SOIQ_ASSIGN_OR_RETURN(writing,
                          reserve_writing(budget, dicom::seg_write_peak_bytes(series->geometry, segments), what, stop));
    written = dicom::write_seg(source, segments, options);
  } else {
    std::vector<dicom::FractionalSegSegment> segments;
    // The coverage, not runs, is admitted (its n^2 crossings); no dense fractions are made: the
    // frames' bytes are counted in the writing's reservation.
    FeatureEngine::WorkExtras extras;
    extras.coverage_lines = oversample;
    for (const db::StructureRecord& s : structures) {
      SOIQ_ASSIGN_OR_RETURN(FeatureEngine::Admission a,
                            features.admit(s, series->geometry, extras, patient_stop(stop, admitted)));
      SOIQ_ASSIGN_OR_RETURN(CoverageVolume c, features.cover(a, s, series->geometry, FillRule::kNonZero, oversample));
      a.shrink_to(coverage_bytes(c));
      admitted.push_back(std::move(a));
      dicom::FractionalSegSegment segment;
      static_cast<dicom::SegSegmentDescription&>(segment) = describe_segment(s, segments.size());
      segment.coverage = std::move(c);
      segments.push_back(std::move(segment));
    }
    SOIQ_ASSIGN_OR_RETURN(
        writing,
        reserve_writing(budget, dicom::fractional_seg_write_peak_bytes(series->geometry, segments), what, stop));
    written = dicom::write_fractional_seg(source, segments, options);
  }
  SOIQ_RETURN_IF_ERROR(written.status());
  // Only the bytes stay: they are counted until the caller lets them go.
  writing.shrink_to(int64_t(written->bytes.capacity()));
  return BudgetedSeg{std::move(*written), std::move(writing)};
}

}  // namespace soiq::server
