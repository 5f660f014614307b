// The patient and study half of every write that adds a structure or a series
// (upsert_patient_and_study, sql_store_writes.h): given fields are merged into the stored
// records, a study never changes patient, and the ages the store computes follow the dates.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "db/age_years.h"
#include "db/record_merge.h"
#include "db/sql/sql_store_writes.h"

namespace soiq::db {
namespace {

// What is stored of a study, for merging; every field empty when the study is new.
struct StoredStudy {
  std::optional<int64_t> pk;  // unset: a new study
  std::string date, description, modality, time, study_id, accession_number;
  std::optional<double> given_age;  // an age that was given, never one the store computed
};

// The study with its owner and the fields an upsert merges.
constexpr char kStudyForUpsertSql[] = R"sql(
  SELECT st.pk, p.patient_id, st.study_date, st.description, st.modality, st.age_years, st.age_given,
         st.study_time, st.study_id, st.accession_number
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE st.study_uid = ?1)sql";

// FAILED_PRECONDITION when the study is stored under another patient than `patient_id`.
Result<StoredStudy> stored_study(SqlSession& c, const std::string& study_uid, const std::string& patient_id) {
  StoredStudy stored;
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kStudyForUpsertSql));
  q.bind(1, study_uid);
  SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
  if (!found) return stored;
  const std::string owner = q.text(1);
  if (owner != patient_id) {
    return failed_precondition("study '" + study_uid + "' belongs to patient '" + owner + "', not to '" + patient_id +
                               "': an upload never moves a study to another patient");
  }
  stored.pk = q.int64(0);
  stored.date = q.text(2);
  stored.description = q.text(3);
  stored.modality = q.text(4);
  if (q.int64(6) != 0) stored.given_age = q.optional_real(5);
  stored.time = q.text(7);
  stored.study_id = q.text(8);
  stored.accession_number = q.text(9);
  return stored;
}

// What is stored of a patient, for merging; every field empty when the patient is new.
struct StoredPatient {
  std::optional<int64_t> pk;  // unset: a new patient
  std::string sex, birth_date, patient_name;
};

constexpr char kPatientForUpsertSql[] = R"sql(
  SELECT pk, sex, birth_date, patient_name FROM patients WHERE patient_id = ?1)sql";

Result<StoredPatient> stored_patient(SqlSession& c, const std::string& patient_id) {
  StoredPatient stored;
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kPatientForUpsertSql));
  q.bind(1, patient_id);
  SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
  if (!found) return stored;
  stored.pk = q.int64(0);
  stored.sex = q.text(1);
  stored.birth_date = q.text(2);
  stored.patient_name = q.text(3);
  return stored;
}

constexpr char kInsertPatientSql[] = R"sql(
  INSERT INTO patients(patient_id, sex, birth_date, patient_name) VALUES (?1, ?2, ?3, ?4)
  RETURNING pk)sql";

constexpr char kUpdatePatientSql[] = R"sql(
  UPDATE patients SET sex = ?2, birth_date = ?3, patient_name = ?4 WHERE pk = ?1)sql";

// Inserts the patient, or updates a stored one whose merged sex, birth date or name differs; returns
// its pk. `birth` is the merged birth date.
Result<int64_t> upsert_patient(SqlSession& c, const PatientRecord& patient, const StoredPatient& stored,
                               const std::string& birth) {
  if (!stored.pk) {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, c.prepare(kInsertPatientSql));
    ins.bind(1, patient.patient_id);
    ins.bind(2, patient.sex);
    ins.bind(3, patient.birth_date);
    ins.bind(4, patient.patient_name);
    SOIQ_ASSIGN_OR_RETURN(const bool row, ins.step());
    if (!row) return internal_error("insert of patient '" + patient.patient_id + "' returned no key");
    return ins.int64(0);
  }
  const std::string& sex = merged(patient.sex, stored.sex);
  const std::string& name = merged(patient.patient_name, stored.patient_name);
  if (sex != stored.sex || birth != stored.birth_date || name != stored.patient_name) {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(kUpdatePatientSql));
    up.bind(1, *stored.pk);
    up.bind(2, sex);
    up.bind(3, birth);
    up.bind(4, name);
    SOIQ_RETURN_IF_ERROR(up.run());
  }
  return *stored.pk;
}

// The update and the insert of a study take the same parameters: ?1 pk, ?2 study_uid, ?3 study_date,
// ?4 description, ?5 modality, ?6 age_years, ?7 age_given, ?8 patient_pk, ?9 study_time,
// ?10 study_id, ?11 accession_number.
constexpr char kUpdateStudySql[] = R"sql(
  UPDATE studies
  SET study_date = ?3, description = ?4, modality = ?5, age_years = ?6, age_given = ?7, study_time = ?9,
      study_id = ?10, accession_number = ?11
  WHERE pk = ?1 AND study_uid = ?2 AND patient_pk = ?8
  RETURNING pk)sql";

constexpr char kInsertStudySql[] = R"sql(
  INSERT INTO studies(study_uid, patient_pk, study_date, description, modality, age_years, age_given,
                      study_time, study_id, accession_number)
  VALUES (?2, ?8, ?3, ?4, ?5, ?6, ?7, ?9, ?10, ?11)
  RETURNING pk)sql";

// Inserts the study or updates the stored one with the merged fields and age; returns its pk.
// `birth` is the patient's merged birth date.
Result<int64_t> upsert_study(SqlSession& c, const StudyRecord& study, const StoredStudy& stored, int64_t patient_pk,
                             const std::string& birth) {
  const std::string& date = merged(study.study_date, stored.date);
  SOIQ_ASSIGN_OR_RETURN(const std::optional<double> age, study_age(study.age_years, stored.given_age, birth, date));
  const bool age_given = study.age_years.has_value() || stored.given_age.has_value();
  SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(stored.pk ? kUpdateStudySql : kInsertStudySql));
  // Both forms use every parameter (an unused one is a bind error); the update's extra
  // conditions hold by the ownership check of stored_study.
  if (stored.pk) up.bind(1, *stored.pk);
  up.bind(2, study.study_uid);
  up.bind(3, date);
  up.bind(4, merged(study.description, stored.description));
  up.bind(5, merged(study.modality, stored.modality));
  up.bind(6, age);
  up.bind(7, int64_t{age_given});
  up.bind(8, patient_pk);
  up.bind(9, merged(study.study_time, stored.time));
  up.bind(10, merged(study.study_id, stored.study_id));
  up.bind(11, merged(study.accession_number, stored.accession_number));
  SOIQ_ASSIGN_OR_RETURN(const bool row, up.step());
  if (!row) return internal_error("upsert of study '" + study.study_uid + "' returned no key");
  return up.int64(0);
}

// The patient's other studies whose age is computed.
constexpr char kStudiesWithComputedAgeSql[] = R"sql(
  SELECT pk, study_date FROM studies WHERE patient_pk = ?1 AND age_given = 0 AND pk <> ?2)sql";

constexpr char kUpdateStudyAgeSql[] = R"sql(
  UPDATE studies SET age_years = ?2 WHERE pk = ?1)sql";

// Recomputes the age of every study of the patient but `study_pk` whose age was not given, from
// the new birth date `birth`.
Status refresh_computed_ages(SqlSession& c, int64_t patient_pk, int64_t study_pk, const std::string& birth) {
  std::vector<std::pair<int64_t, std::string>> others;
  {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kStudiesWithComputedAgeSql));
    q.bind(1, patient_pk);
    q.bind(2, study_pk);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      others.emplace_back(q.int64(0), q.text(1));
    }
  }
  for (const auto& [pk, other_date] : others) {
    // A stored date that no longer parses cannot be: it was validated when stored.
    SOIQ_ASSIGN_OR_RETURN(const std::optional<double> other_age, age_years(birth, other_date));
    SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(kUpdateStudyAgeSql));
    up.bind(1, pk);
    up.bind(2, other_age);
    SOIQ_RETURN_IF_ERROR(up.run());
  }
  return ok_status();
}

}  // namespace

Result<StudyKeys> upsert_patient_and_study(SqlSession& c, const PatientRecord& patient, const StudyRecord& study) {
  // The ownership check comes first so that a refused study leaves no patient behind even
  // without the rollback.
  SOIQ_ASSIGN_OR_RETURN(const StoredStudy old_study, stored_study(c, study.study_uid, patient.patient_id));
  SOIQ_ASSIGN_OR_RETURN(const StoredPatient old_patient, stored_patient(c, patient.patient_id));
  const std::string& birth = merged(patient.birth_date, old_patient.birth_date);
  StudyKeys keys;
  SOIQ_ASSIGN_OR_RETURN(keys.patient_pk, upsert_patient(c, patient, old_patient, birth));
  SOIQ_ASSIGN_OR_RETURN(keys.study_pk, upsert_study(c, study, old_study, keys.patient_pk, birth));
  if (old_patient.pk && birth != old_patient.birth_date) {
    // The birth date changed: every computed age of this patient's other studies moves with it.
    SOIQ_RETURN_IF_ERROR(refresh_computed_ages(c, keys.patient_pk, keys.study_pk, birth));
  }
  return keys;
}

}  // namespace soiq::db
