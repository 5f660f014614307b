#include "db/validate_records.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/base/field_rules.h"
#include "db/age_years.h"
#include "db/surface_blob.h"

namespace soiq::db {

Status validate_text(const std::string& value, const std::string& what, size_t max_bytes) {
  return check_text(value, max_bytes).in_field(what);
}

Status validate_sex(const std::string& sex) { return check_sex(sex).in_field("sex"); }

Status validate_laterality(const std::string& laterality) {
  return check_laterality(laterality).in_field("laterality");
}

Status validate_sha256(const std::string& sha256, const std::string& what) {
  bool ok = sha256.size() == 64;
  for (char c : sha256) ok = ok && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
  if (ok) return ok_status();
  return invalid_argument(what + " sha256 '" + sha256 + "' is not 64 lower-case hex digits");
}

Status validate_uid(const std::string& uid, const std::string& what) { return check_uid(uid).in_field(what); }

Status validate_patient(const PatientRecord& p) {
  SOIQ_RETURN_IF_ERROR(check_id(p.patient_id).in_field("patient_id"));
  SOIQ_RETURN_IF_ERROR(validate_sex(p.sex));
  // The name itself is never quoted: messages reach logs.
  SOIQ_RETURN_IF_ERROR(
      check_text(p.patient_name, kMaxNameBytes, false).in_field("name of patient '" + p.patient_id + "'"));
  return check_date(p.birth_date).in_field("birth date of patient '" + p.patient_id + "'");
}

Status validate_study(const StudyRecord& s, const std::string& patient_id) {
  SOIQ_RETURN_IF_ERROR(check_id(s.study_uid).in_field("study_uid"));
  SOIQ_RETURN_IF_ERROR(validate_text(s.description, "study description", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.modality, "study modality", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.study_time, "study time", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.study_id, "study id", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.accession_number, "accession number", kMaxIdBytes));
  if (!s.patient_id.empty() && s.patient_id != patient_id) {
    return invalid_argument("study '" + s.study_uid + "' names patient '" + s.patient_id +
                            "' but is sent with patient '" + patient_id + "'");
  }
  if (s.age_years) SOIQ_RETURN_IF_ERROR(check_age_years(*s.age_years).in_field("age of study '" + s.study_uid + "'"));
  return check_date(s.study_date).in_field("study date of study '" + s.study_uid + "'");
}

Status validate_stage1_filter(const Stage1Filter& f) {
  SOIQ_RETURN_IF_ERROR(validate_text(f.patient_id_glob, "patient id glob", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.modality, "modality", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.study_description_glob, "study description glob", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.structure_name_glob, "structure name glob", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_sex(f.sex));
  SOIQ_RETURN_IF_ERROR(validate_laterality(f.laterality));
  SOIQ_RETURN_IF_ERROR(check_date(f.birth_date_from).in_field("birth_date_from"));
  SOIQ_RETURN_IF_ERROR(check_date(f.birth_date_to).in_field("birth_date_to"));
  SOIQ_RETURN_IF_ERROR(check_date(f.study_date_from).in_field("study_date_from"));
  SOIQ_RETURN_IF_ERROR(check_date(f.study_date_to).in_field("study_date_to"));
  if (f.min_age_years) SOIQ_RETURN_IF_ERROR(check_age_years(*f.min_age_years).in_field("min_age_years"));
  if (f.max_age_years) SOIQ_RETURN_IF_ERROR(check_age_years(*f.max_age_years).in_field("max_age_years"));
  for (const StoredFeatureCondition& c : f.stored_features) {
    const auto& names = stored_feature_names();
    if (std::find(names.begin(), names.end(), c.name) == names.end())
      return invalid_argument("'" + c.name + "' is not a stored feature");
    if (!comparison_of_symbol(comparison_symbol(c.op)))
      return invalid_argument("a stored-feature condition on '" + c.name + "' has no comparison");
    if (std::isnan(c.value))
      return invalid_argument("a stored-feature condition on '" + c.name + "' compares with NaN");
  }
  if (f.min_age_years && f.max_age_years && *f.min_age_years > *f.max_age_years) {
    return invalid_argument("min_age_years " + std::to_string(*f.min_age_years) + " is above max_age_years " +
                            std::to_string(*f.max_age_years));
  }
  return ok_status();
}

Status validate_patient_filter(const PatientFilter& f) {
  SOIQ_RETURN_IF_ERROR(validate_text(f.patient_id_glob, "patient id glob", kMaxNameBytes));
  return validate_sex(f.sex);
}

Status validate_structure_filter(const StructureFilter& f) {
  SOIQ_RETURN_IF_ERROR(validate_text(f.patient_id, "patient_id", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.study_uid, "study_uid", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.name_glob, "structure name glob", kMaxNameBytes));
  return validate_laterality(f.laterality);
}

Status validate_cache_entries(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) {
  SOIQ_RETURN_IF_ERROR(validate_sha256(surface_sha256, "surface"));
  for (const CachedFeature& f : entries) {
    if (f.key.empty() || f.entry.empty()) return invalid_argument("a cached feature needs a key and an entry name");
  }
  return ok_status();
}

namespace {

// One kept instance of the series `s` (NewInstance): refusals name the instance.
Status validate_instance(const NewSeries& s, const NewInstance& i, const std::set<std::string>& slice_uids) {
  const InstanceRecord& r = i.record;
  const std::string what = "instance '" + r.sop_instance_uid + "' of series '" + s.series.series_uid + "'";
  if (r.sop_instance_uid.empty())
    return invalid_argument("an instance of series '" + s.series.series_uid + "' has no SOP Instance UID");
  if (slice_uids.count(r.sop_instance_uid) == 0)
    return invalid_argument(what + " is not one of the series' slice instance uids");
  if (r.series_uid != s.series.series_uid) return invalid_argument(what + " names series '" + r.series_uid + "'");
  if (r.slice < 0 || r.slice >= s.series.geometry.dims[2])
    return invalid_argument(what + " has slice " + std::to_string(r.slice) + ", outside 0.." +
                            std::to_string(s.series.geometry.dims[2] - 1));
  if (i.file.empty()) return invalid_argument(what + " has an empty file");
  if (r.file_bytes != int64_t(i.file.size()))
    return invalid_argument(what + " says its file has " + std::to_string(r.file_bytes) + " bytes, not " +
                            std::to_string(i.file.size()));
  // The store keys the file by this sha256 and checks the bytes against it on every read.
  if (r.file_sha256 != sha256_hex(i.file.data(), i.file.size()))
    return invalid_argument(what + " has a file_sha256 that is not its file's sha256");
  if (r.metadata.empty() || r.metadata.front() != '{')
    return invalid_argument(what + " has metadata that is not a JSON object");
  return ok_status();
}

// The series' instances, each once.
Status validate_instances(const NewSeries& s) {
  if (s.instances.empty()) return ok_status();
  const std::set<std::string> slice_uids(s.series.slice_instance_uids.begin(), s.series.slice_instance_uids.end());
  std::set<std::string> seen;
  for (const NewInstance& i : s.instances) {
    SOIQ_RETURN_IF_ERROR(validate_instance(s, i, slice_uids));
    if (!seen.insert(i.record.sop_instance_uid).second)
      return invalid_argument("instance '" + i.record.sop_instance_uid + "' of series '" + s.series.series_uid +
                              "' is sent twice");
  }
  return ok_status();
}

}  // namespace

Status validate_new_series(const NewSeries& s) {
  SOIQ_RETURN_IF_ERROR(validate_patient(s.patient));
  SOIQ_RETURN_IF_ERROR(validate_study(s.study, s.patient.patient_id));
  SOIQ_RETURN_IF_ERROR(check_id(s.series.series_uid).in_field("series_uid"));
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.modality, "modality", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.description, "series description", kMaxNameBytes));
  if (s.series.series_number < 0 || s.series.series_number > 2147483647)
    return invalid_argument("series number " + std::to_string(s.series.series_number) + " is outside 0..2^31-1");
  if (!std::isfinite(s.series.window_center) || !std::isfinite(s.series.window_width) || s.series.window_width < 0)
    return invalid_argument("series window " + std::to_string(s.series.window_center) + "," +
                            std::to_string(s.series.window_width) + " is not a finite centre and a width >= 0");
  if (!s.series.study_uid.empty() && s.series.study_uid != s.study.study_uid) {
    return invalid_argument("series '" + s.series.series_uid + "' names study '" + s.series.study_uid +
                            "' but is sent with study '" + s.study.study_uid + "'");
  }
  SOIQ_RETURN_IF_ERROR(validate_geometry(s.series.geometry));
  SOIQ_RETURN_IF_ERROR(validate_sha256(s.series.sha256, "image"));
  SOIQ_RETURN_IF_ERROR(validate_uid(s.series.frame_of_reference_uid, "frame_of_reference_uid"));
  SOIQ_RETURN_IF_ERROR(validate_uid(s.series.sop_class_uid, "sop_class_uid"));
  for (const std::string& uid : s.series.slice_instance_uids)
    SOIQ_RETURN_IF_ERROR(validate_uid(uid, "slice instance uid"));
  if (!s.series.slice_instance_uids.empty() &&
      int64_t(s.series.slice_instance_uids.size()) != s.series.geometry.dims[2]) {
    return invalid_argument("series '" + s.series.series_uid + "' has " +
                            std::to_string(s.series.slice_instance_uids.size()) + " slice instance uids for " +
                            std::to_string(s.series.geometry.dims[2]) + " slices");
  }
  if (s.image_blob.empty()) return invalid_argument("image blob is empty");
  return validate_instances(s);
}

Status validate_new_structure(const NewStructure& s) {
  SOIQ_RETURN_IF_ERROR(validate_patient(s.patient));
  SOIQ_RETURN_IF_ERROR(validate_study(s.study, s.patient.patient_id));
  if (s.name.empty()) return invalid_argument("structure name is empty");
  SOIQ_RETURN_IF_ERROR(validate_text(s.name, "structure name", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_laterality(s.laterality));
  SOIQ_RETURN_IF_ERROR(validate_sha256(s.surface.sha256, "surface"));
  if (s.surface_blob.empty()) return invalid_argument("surface blob is empty");
  SOIQ_RETURN_IF_ERROR(validate_uid(s.source_series_uid, "source_series_uid"));
  return ok_status();
}

Status validate_precomputed(const Precomputed& p) {
  SOIQ_RETURN_IF_ERROR(validate_sha256(p.surface_sha256, "surface"));
  const size_t n = stored_feature_names().size();
  if (p.failure.empty() && p.values.size() != n) {
    return invalid_argument("precomputed values: " + std::to_string(p.values.size()) + " given, " + std::to_string(n) +
                            " stored features");
  }
  if (p.set != PrecomputedSet::kDefault && p.set != PrecomputedSet::kWithWeighted) {
    return invalid_argument("precomputed set " + std::to_string(int(p.set)) + " is none of soiqd's");
  }
  for (const CachedFeature& f : p.cache_entries) {
    if (f.key.empty() || f.entry.empty()) return invalid_argument("a cached feature needs a key and an entry name");
  }
  return ok_status();
}

}  // namespace soiq::db
