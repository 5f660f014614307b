#include "db/validate_records.h"

#include <algorithm>
#include <cmath>

#include "core/base/utf8.h"
#include "db/age_years.h"

namespace soiq::db {

namespace {

// The value as a message may quote it: 40 bytes at most, control bytes as '?'.
std::string quoted(const std::string& value) {
  std::string q = value.substr(0, 40);
  for (char& c : q) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return "'" + q + (value.size() > 40 ? "...'" : "'");
}

}  // namespace

Status validate_text(const std::string& value, const std::string& what, size_t max_bytes) {
  if (value.size() > max_bytes) {
    return invalid_argument(what + " " + quoted(value) + " is " + std::to_string(value.size()) +
                            " bytes long; the limit is " + std::to_string(max_bytes));
  }
  for (const char c : value) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return invalid_argument(what + " " + quoted(value) + " contains a control character (newline, tab, ...)");
    }
  }
  return ok_status();
}

Status validate_sex(const std::string& sex) {
  if (sex.empty() || sex == "M" || sex == "F" || sex == "O") return ok_status();
  return invalid_argument("sex '" + sex + "' is not one of M, F, O or empty");
}

Status validate_laterality(const std::string& laterality) {
  if (laterality.empty() || laterality == "L" || laterality == "R") return ok_status();
  return invalid_argument("laterality '" + laterality + "' is not one of L, R or empty");
}

Status validate_sha256(const std::string& sha256, const std::string& what) {
  bool ok = sha256.size() == 64;
  for (char c : sha256) ok = ok && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
  if (ok) return ok_status();
  return invalid_argument(what + " sha256 '" + sha256 + "' is not 64 lower-case hex digits");
}

Status validate_uid(const std::string& uid, const std::string& what) {
  bool ok = uid.size() <= 64;
  for (char c : uid) ok = ok && ((c >= '0' && c <= '9') || c == '.');
  if (ok) return ok_status();
  return invalid_argument(what + " '" + uid + "' is not a DICOM UID (at most 64 digits and dots)");
}

Status validate_patient(const PatientRecord& p) {
  if (p.patient_id.empty()) return invalid_argument("patient_id is empty");
  SOIQ_RETURN_IF_ERROR(validate_text(p.patient_id, "patient_id", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_sex(p.sex));
  // The name itself is never quoted: messages reach logs.
  if (!validate_text(p.patient_name, "", kMaxNameBytes).ok() || !is_utf8(p.patient_name))
    return invalid_argument("the name of patient '" + p.patient_id + "' is longer than " +
                            std::to_string(kMaxNameBytes) + " bytes, has a control character or is not UTF-8");
  return validate_date(p.birth_date, "birth date of patient '" + p.patient_id + "'");
}

Status validate_study(const StudyRecord& s, const std::string& patient_id) {
  if (s.study_uid.empty()) return invalid_argument("study_uid is empty");
  SOIQ_RETURN_IF_ERROR(validate_text(s.study_uid, "study_uid", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.description, "study description", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.modality, "study modality", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.study_time, "study time", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.study_id, "study id", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.accession_number, "accession number", kMaxIdBytes));
  if (!s.patient_id.empty() && s.patient_id != patient_id) {
    return invalid_argument("study '" + s.study_uid + "' names patient '" + s.patient_id +
                            "' but is sent with patient '" + patient_id + "'");
  }
  if (s.age_years && !(std::isfinite(*s.age_years) && *s.age_years >= 0)) {
    return invalid_argument("age of study '" + s.study_uid + "' must be finite and >= 0, got " +
                            std::to_string(*s.age_years));
  }
  return validate_date(s.study_date, "study date of study '" + s.study_uid + "'");
}

Status validate_stage1_filter(const Stage1Filter& f) {
  SOIQ_RETURN_IF_ERROR(validate_text(f.patient_id_glob, "patient id glob", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.modality, "modality", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.study_description_glob, "study description glob", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(f.structure_name_glob, "structure name glob", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(validate_sex(f.sex));
  SOIQ_RETURN_IF_ERROR(validate_laterality(f.laterality));
  SOIQ_RETURN_IF_ERROR(validate_date(f.birth_date_from, "birth_date_from"));
  SOIQ_RETURN_IF_ERROR(validate_date(f.birth_date_to, "birth_date_to"));
  SOIQ_RETURN_IF_ERROR(validate_date(f.study_date_from, "study_date_from"));
  SOIQ_RETURN_IF_ERROR(validate_date(f.study_date_to, "study_date_to"));
  for (const auto& age : {f.min_age_years, f.max_age_years}) {
    if (age && !std::isfinite(*age)) return invalid_argument("age bounds must be finite");
  }
  for (const StoredFeatureCondition& c : f.stored_features) {
    const auto& names = stored_feature_names();
    if (std::find(names.begin(), names.end(), c.name) == names.end())
      return invalid_argument("'" + c.name + "' is not a stored feature");
    static const std::vector<std::string> kOps = {"<", "<=", ">", ">=", "=", "!="};
    if (std::find(kOps.begin(), kOps.end(), c.op) == kOps.end())
      return invalid_argument("'" + c.op + "' is not a comparison (< <= > >= = !=)");
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

Status validate_new_series(const NewSeries& s) {
  SOIQ_RETURN_IF_ERROR(validate_patient(s.patient));
  SOIQ_RETURN_IF_ERROR(validate_study(s.study, s.patient.patient_id));
  if (s.series.series_uid.empty()) return invalid_argument("series_uid is empty");
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.series_uid, "series_uid", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.modality, "modality", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.description, "series description", kMaxNameBytes));
  if (s.series.series_number < 0 || s.series.series_number > 2147483647)
    return invalid_argument("series number " + std::to_string(s.series.series_number) + " is outside 0..2^31-1");
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
  return ok_status();
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
  for (const CachedFeature& f : p.cache_entries) {
    if (f.key.empty() || f.entry.empty()) return invalid_argument("a cached feature needs a key and an entry name");
  }
  return ok_status();
}

}  // namespace soiq::db
