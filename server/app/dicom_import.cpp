#include "server/app/dicom_import.h"

#include <chrono>
#include <map>
#include <optional>

#include "core/base/field_rules.h"
#include "core/base/run_length_volume.h"
#include "db/age_years.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"
#include "db/validate_records.h"
#include "dicom/import_dicom.h"
#include "server/app/dicom_import_bytes.h"
#include "server/app/kept_instances.h"
#include "server/util/log.h"

namespace soiq::server {
namespace {

// Paths inside the receiving folder, as the client named them.
struct Relative {
  std::string prefix;  // "<dir>/"
  std::string operator()(std::string text) const {
    for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at))
      text.erase(at, prefix.size());
    return text;
  }
};

void add_problem(DicomImportResult& r, const std::string& path, StatusCode code, const std::string& message) {
  r.problems.push_back({path, code, message});
}

// DICOM values the store would refuse are dropped rather than failing the import: the series and
// structures are still useful without them.
db::PatientRecord patient_of(const dicom::DicomPatient& p, bool keep_name) {
  db::PatientRecord r;
  r.patient_id = p.patient_id;
  if (keep_name && db::validate_text(p.name, "", db::kMaxNameBytes).ok()) r.patient_name = p.name;
  if (db::validate_sex(p.sex).ok()) r.sex = p.sex;
  if (check_date(p.birth_date).ok()) r.birth_date = p.birth_date;
  return r;
}

db::StudyRecord study_of(const dicom::DicomStudy& s) {
  db::StudyRecord r;
  r.study_uid = s.study_uid;
  r.patient_id = s.patient_id;
  if (check_date(s.study_date).ok()) r.study_date = s.study_date;
  // Kept for the SEGs soiq writes on the study (server/app/structure_seg.h), which checks each against
  // its VR; here only what the store takes.
  const auto storable = [](const std::string& v) { return db::validate_text(v, "", db::kMaxIdBytes).ok(); };
  if (storable(s.study_time)) r.study_time = s.study_time;
  if (storable(s.study_id)) r.study_id = s.study_id;
  if (storable(s.accession_number)) r.accession_number = s.accession_number;
  if (check_text(s.description, kMaxNameBytes).ok()) r.description = s.description;
  r.age_years = s.age_years;
  return r;
}

std::string laterality_of(const std::string& name) {
  if (name.size() < 3) return "";
  const std::string tail = name.substr(name.size() - 2);
  if (tail == "_L" || tail == " L") return "L";
  if (tail == "_R" || tail == " R") return "R";
  return "";
}

// The patient and study records a series belongs to; NOT_FOUND when the scan lacks them (cannot
// happen for scanned series, checked anyway since the two come from different lists).
Status records_of(const dicom::DicomScan& scan, const std::string& series_uid, bool keep_names,
                  db::PatientRecord& patient, db::StudyRecord& study) {
  const dicom::DicomSeries* series = scan.find_series(series_uid);
  const dicom::DicomStudy* st = series ? scan.find_study(series->study_uid) : nullptr;
  const dicom::DicomPatient* p = st ? scan.find_patient(st->patient_id) : nullptr;
  if (p == nullptr) return not_found("series " + series_uid + " has no study or patient in the files sent");
  patient = patient_of(*p, keep_names);
  study = study_of(*st);
  return ok_status();
}

// The stored patient and study of a stored series (a structure set or SEG sent without its images).
Status stored_records_of(db::RecordStore& store, const std::string& series_uid, db::PatientRecord& patient,
                         db::StudyRecord& study) {
  SOIQ_ASSIGN_OR_RETURN(const db::SeriesRecord series, store.get_series(series_uid));
  SOIQ_ASSIGN_OR_RETURN(study, store.get_study(series.study_uid));
  SOIQ_ASSIGN_OR_RETURN(patient, store.get_patient(study.patient_id));
  return ok_status();
}

// Series soiq already stores, for dicom::import_dicom's FindKnownSeries.
dicom::FindKnownSeries stored_series(db::RecordStore& store) {
  return [&store](const std::string& uid) -> std::optional<dicom::KnownSeries> {
    Result<db::SeriesRecord> s = store.get_series(uid);
    if (!s.ok()) return std::nullopt;
    Result<db::StudyRecord> study = store.get_study(s->study_uid);
    if (!study.ok()) return std::nullopt;
    return dicom::KnownSeries{s->series_uid, s->study_uid, study->patient_id, s->frame_of_reference_uid, s->geometry};
  };
}

struct Planned {
  db::ImportBatch batch;
  std::vector<std::string> referenced_series;  // by structure
  std::vector<int64_t> voxel_counts;           // by structure
};

Result<Planned> plan(db::RecordStore& store, const dicom::DicomImport& in, const Relative& rel,
                     const DicomImportOptions& options, DicomImportResult& r) {
  const bool keep_names = options.keep_patient_names;
  const bool replace = options.replace;
  Planned out;
  for (const dicom::SeriesImage& image : in.images) {
    db::NewSeries s;
    SOIQ_RETURN_IF_ERROR(records_of(in.scan, image.series_uid, keep_names, s.patient, s.study));
    SOIQ_ASSIGN_OR_RETURN(db::EncodedImage encoded, db::encode_image(image.image));
    s.series.series_uid = image.series_uid;
    s.series.study_uid = s.study.study_uid;
    s.series.modality = image.modality;
    s.series.geometry = image.image.geometry;
    s.series.sha256 = encoded.sha256;
    // The DICOM references a SEG derived from this series needs (dicom/seg_export.h).
    if (const dicom::DicomSeries* scanned = in.scan.find_series(image.series_uid)) {
      s.series.frame_of_reference_uid = scanned->frame_of_reference_uid;
      if (!scanned->instances.empty()) s.series.sop_class_uid = scanned->instances.front().sop_class_uid;
      if (scanned->series_number >= 0 && scanned->series_number <= 2147483647)
        s.series.series_number = scanned->series_number;
      if (db::validate_text(scanned->description, "", db::kMaxNameBytes).ok())
        s.series.description = scanned->description;
      // A PET series' window is in its stored units, not the SUV its voxels become.
      if (image.modality != "PT" && image.modality != "NM") {
        s.series.window_center = scanned->window_center;
        s.series.window_width = scanned->window_width;
      }
      if (options.keep_instances) {
        Result<std::vector<db::NewInstance>> kept = kept_instances(*scanned, image.slice_sop_instance_uids);
        if (!kept.ok()) return Status(kept.status().code(), rel(kept.status().message()));
        s.instances = std::move(kept).value();
      }
    }
    s.series.slice_instance_uids = image.slice_sop_instance_uids;
    s.image_blob = std::move(encoded.blob);
    s.replace_other_content = replace;
    out.batch.series.push_back(std::move(s));
  }
  for (const std::string& failed : in.failed_structure_sets) r.structure_sets_without_structures.push_back(rel(failed));
  for (const dicom::ImportedStructureSet& set : in.structure_sets) {
    const std::string path = rel(set.path);
    const std::string what = set.segmentation ? "segment" : "ROI";
    const size_t stored_before = out.batch.structures.size();
    for (const dicom::SkippedRoi& roi : set.converted.skipped) {
      add_problem(r, path, StatusCode::kInvalidArgument,
                  what + " '" + roi.name + "' (number " + std::to_string(roi.roi_number) + ") skipped: " + roi.reason);
    }
    for (const dicom::ImportedStructure& roi : set.converted.structures) {
      const std::string name = roi.name.empty() ? what + " " + std::to_string(roi.roi_number) : roi.name;
      if (roi.surface.triangles.empty()) {
        add_problem(r, path, StatusCode::kInvalidArgument,
                    what + " '" + name + "' skipped: it covers no voxel centre of series " + set.referenced_series_uid);
        continue;
      }
      db::NewStructure s;
      if (set.on_known_series) {
        SOIQ_RETURN_IF_ERROR(stored_records_of(store, set.referenced_series_uid, s.patient, s.study));
      } else {
        SOIQ_RETURN_IF_ERROR(records_of(in.scan, set.referenced_series_uid, keep_names, s.patient, s.study));
      }
      s.name = name;
      s.laterality = laterality_of(name);
      s.source_series_uid = set.referenced_series_uid;
      s.source_uid = set.sop_instance_uid + "/" + std::to_string(roi.roi_number);
      // A SEG segment with exactly the voxels and name of a structure already on its series is
      // that structure, typically soiq's own export coming back from a PACS: a second copy would
      // double every cohort count. RT Structure Sets keep replace-by-source-uid only: their ROIs
      // are the originals that SEGs are exported from.
      s.same_content_is_same_structure = set.segmentation;
      s.replace_other_content = replace;
      SOIQ_ASSIGN_OR_RETURN(db::EncodedSurface encoded, db::encode_surface(roi.surface));
      s.surface = encoded.info;
      s.surface_blob = std::move(encoded.blob);
      out.batch.structures.push_back(std::move(s));
      out.referenced_series.push_back(set.referenced_series_uid);
      out.voxel_counts.push_back(voxel_count(roi.volume));
      if (roi.contours_superseded > 0) {
        add_problem(r, path, StatusCode::kInvalidArgument,
                    what + " '" + name + "': " + std::to_string(roi.contours_superseded) +
                        " contours left out, another plane's contours being nearer their image slice (drawn on a "
                        "finer series than " +
                        set.referenced_series_uid + "?)");
      }
    }
    if (out.batch.structures.size() == stored_before) r.structure_sets_without_structures.push_back(path);
  }
  return out;
}

void list_records(const db::ImportBatch& batch, DicomImportResult& r) {
  std::map<std::string, db::PatientRecord> patients;
  std::map<std::string, db::StudyRecord> studies;
  for (const auto& s : batch.series) {
    patients.emplace(s.patient.patient_id, s.patient);
    studies.emplace(s.study.study_uid, s.study);
  }
  for (const auto& s : batch.structures) {
    patients.emplace(s.patient.patient_id, s.patient);
    studies.emplace(s.study.study_uid, s.study);
  }
  for (const auto& [id, p] : patients) r.patients.push_back(p);
  for (const auto& [uid, s] : studies) r.studies.push_back(s);
}

}  // namespace

Result<DicomImportResult> import_dicom_folder(db::RecordStore& store, const std::string& dir,
                                              const std::vector<std::string>& sent, int64_t max_voxels,
                                              MemoryBudget& budget, const std::function<Status()>& stop,
                                              const DicomImportOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const Relative rel{dir + "/"};
  // Held to the end: the decoded images and their blobs live until the write is done.
  MemoryBudget::Reservation held;
  auto admit = [&](const dicom::DicomScan& scan) -> Status {
    const DicomImportBytes need = dicom_import_bytes(scan, max_voxels);
    if (need.series == 0) return ok_status();
    const int64_t files = options.keep_instances ? kept_instance_bytes(scan) : 0;
    SOIQ_ASSIGN_OR_RETURN(held, budget.reserve(need.bytes + files, need.what, stop,
                                               need.series > 1 ? "import fewer series at once, or raise the budget"
                                                               : "raise the budget"));
    return ok_status();
  };
  SOIQ_ASSIGN_OR_RETURN(const dicom::DicomImport in,
                        dicom::import_dicom({dir}, max_voxels, stored_series(store), admit));
  DicomImportResult r;
  r.files_received = int64_t(sent.size());
  r.dicom_files_read = in.scan.files_read;
  for (const dicom::FileProblem& p : in.problems) add_problem(r, rel(p.path), p.status.code(), rel(p.status.message()));
  if (in.scan.non_dicom_skipped > 0) {
    add_problem(r, "", StatusCode::kInvalidArgument,
                std::to_string(in.scan.non_dicom_skipped) + " of the files sent are not DICOM and were skipped");
  }
  SOIQ_ASSIGN_OR_RETURN(Planned planned, plan(store, in, rel, options, r));
  if (planned.batch.series.empty() && planned.batch.structures.empty()) {
    const std::string why = !r.problems.empty() && !r.problems[0].path.empty()
                                ? r.problems[0].path + ": " + r.problems[0].message
                                : "no CT, MR or PET series and no RT Structure Set in '" +
                                      (sent.empty() ? "" : sent[0]) + "'" +
                                      (sent.size() > 1 ? " and the other files" : "");
    return invalid_argument("nothing could be imported from the " + std::to_string(sent.size()) +
                            " file(s) sent: " + why);
  }
  // Last look before the one write: a client that gave up (Ctrl-C) while its files were decoded
  // gets nothing stored, as it is told.
  if (stop) SOIQ_RETURN_IF_ERROR(stop());
  SOIQ_ASSIGN_OR_RETURN(const db::ImportedBatch stored, store.import_batch(planned.batch));
  // What an import asked to replace, it may have replaced: a DICOM UID's content changed, which an
  // operator must be able to find later.
  if (options.replace) {
    for (size_t i = 0; i < stored.series_replaced.size(); ++i)
      if (stored.series_replaced[i])
        log_event("warning", {{"event", "dicom_replaced"}, {"series", planned.batch.series[i].series.series_uid}});
    for (const db::AddedStructure& s : stored.structures)
      if (s.replaced)
        log_event("warning", {{"event", "dicom_replaced"},
                              {"structure", std::to_string(s.structure.id)},
                              {"source", s.structure.source_uid}});
  }
  list_records(planned.batch, r);
  for (const auto& s : planned.batch.series) r.series.push_back(s.series);
  for (size_t i = 0; i < stored.structures.size(); ++i) {
    // Recognised counts as imported before: the result names the stored structure, same id.
    r.structures.push_back({stored.structures[i].structure, planned.referenced_series[i], planned.voxel_counts[i],
                            stored.structures[i].replaced || stored.structures[i].recognised});
  }
  r.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace soiq::server
