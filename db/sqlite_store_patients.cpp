// The patient and study half of every write that adds a structure or a series
// (upsert_patient_and_study, sqlite_store_writes.h): given fields are merged into the stored
// records, a study never changes patient, and the ages the store computes follow the dates.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "db/age_years.h"
#include "db/sqlite_store_writes.h"

namespace soiq::db {
namespace {

// Chooses the stored age of a study: the given one, else a previously given one, else computed.
Result<std::optional<double>> study_age(const std::optional<double>& given, const std::optional<double>& stored_given,
                                        const std::string& birth_date, const std::string& study_date) {
  if (given) return given;
  if (stored_given) return stored_given;
  return age_years(birth_date, study_date);
}

const std::string& merged(const std::string& given, const std::string& stored) {
  return given.empty() ? stored : given;
}

// The study with its owner and the fields an upsert merges.
constexpr char kStudyForUpsertSql[] = R"sql(
  SELECT st.pk, p.patient_id, st.study_date, st.description, st.modality, st.age_years, st.age_given,
         st.study_time, st.study_id, st.accession_number
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE st.study_uid = ?1)sql";

constexpr char kPatientForUpsertSql[] = R"sql(
  SELECT pk, sex, birth_date FROM patients WHERE patient_id = ?1)sql";

constexpr char kInsertPatientSql[] = R"sql(
  INSERT INTO patients(patient_id, sex, birth_date) VALUES (?1, ?2, ?3)
  RETURNING pk)sql";

constexpr char kUpdatePatientSql[] = R"sql(
  UPDATE patients SET sex = ?2, birth_date = ?3 WHERE pk = ?1)sql";

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

// The patient's other studies whose age is computed.
constexpr char kStudiesWithComputedAgeSql[] = R"sql(
  SELECT pk, study_date FROM studies WHERE patient_pk = ?1 AND age_given = 0 AND pk <> ?2)sql";

constexpr char kUpdateStudyAgeSql[] = R"sql(
  UPDATE studies SET age_years = ?2 WHERE pk = ?1)sql";

}  // namespace

// Inserts or updates the patient and the study (non-empty given fields overwrite), and keeps the
// computed ages of the patient's studies in step with the dates. INVALID_ARGUMENT when the study
// belongs to another patient. Inputs are validated by the caller.
Result<StudyKeys> upsert_patient_and_study(Connection& c, const PatientRecord& patient, const StudyRecord& study) {
  // The ownership check comes first so that a refused study leaves no patient behind even
  // without the rollback.
  std::optional<int64_t> study_pk;
  std::string stored_date, stored_description, stored_modality, stored_time, stored_study_id, stored_accession;
  std::optional<double> stored_given_age;
  {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kStudyForUpsertSql));
    q.bind(1, study.study_uid);
    SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
    if (found) {
      const std::string owner = q.text(1);
      if (owner != patient.patient_id) {
        return failed_precondition("study '" + study.study_uid + "' belongs to patient '" + owner + "', not to '" +
                                   patient.patient_id + "': an upload never moves a study to another patient");
      }
      study_pk = q.int64(0);
      stored_date = q.text(2);
      stored_description = q.text(3);
      stored_modality = q.text(4);
      if (q.int64(6) != 0) stored_given_age = q.optional_real(5);
      stored_time = q.text(7);
      stored_study_id = q.text(8);
      stored_accession = q.text(9);
    }
  }

  StudyKeys keys;
  std::string stored_sex, stored_birth;
  bool patient_found = false;
  {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kPatientForUpsertSql));
    q.bind(1, patient.patient_id);
    SOIQ_ASSIGN_OR_RETURN(patient_found, q.step());
    if (patient_found) {
      keys.patient_pk = q.int64(0);
      stored_sex = q.text(1);
      stored_birth = q.text(2);
    }
  }
  const std::string& birth = merged(patient.birth_date, stored_birth);
  if (!patient_found) {
    SOIQ_ASSIGN_OR_RETURN(Statement ins, c.prepare(kInsertPatientSql));
    ins.bind(1, patient.patient_id);
    ins.bind(2, patient.sex);
    ins.bind(3, patient.birth_date);
    SOIQ_ASSIGN_OR_RETURN(const bool row, ins.step());
    if (!row) return internal_error("insert of patient '" + patient.patient_id + "' returned no key");
    keys.patient_pk = ins.int64(0);
  } else if (merged(patient.sex, stored_sex) != stored_sex || birth != stored_birth) {
    SOIQ_ASSIGN_OR_RETURN(Statement up, c.prepare(kUpdatePatientSql));
    up.bind(1, keys.patient_pk);
    up.bind(2, merged(patient.sex, stored_sex));
    up.bind(3, birth);
    SOIQ_RETURN_IF_ERROR(up.run());
  }

  const std::string& date = merged(study.study_date, stored_date);
  SOIQ_ASSIGN_OR_RETURN(const std::optional<double> age, study_age(study.age_years, stored_given_age, birth, date));
  const bool age_given = study.age_years.has_value() || stored_given_age.has_value();
  {
    SOIQ_ASSIGN_OR_RETURN(Statement up, c.prepare(study_pk ? kUpdateStudySql : kInsertStudySql));
    // Both forms use every parameter (an unused one is a bind error); the update's extra
    // conditions hold by the ownership check above.
    if (study_pk) up.bind(1, *study_pk);
    up.bind(2, study.study_uid);
    up.bind(3, date);
    up.bind(4, merged(study.description, stored_description));
    up.bind(5, merged(study.modality, stored_modality));
    up.bind(6, age);
    up.bind(7, int64_t{age_given});
    up.bind(8, keys.patient_pk);
    up.bind(9, merged(study.study_time, stored_time));
    up.bind(10, merged(study.study_id, stored_study_id));
    up.bind(11, merged(study.accession_number, stored_accession));
    SOIQ_ASSIGN_OR_RETURN(const bool row, up.step());
    if (!row) return internal_error("upsert of study '" + study.study_uid + "' returned no key");
    keys.study_pk = up.int64(0);
  }

  if (patient_found && birth != stored_birth) {
    // The birth date changed: every computed age of this patient's other studies moves with it.
    std::vector<std::pair<int64_t, std::string>> others;
    {
      SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kStudiesWithComputedAgeSql));
      q.bind(1, keys.patient_pk);
      q.bind(2, keys.study_pk);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        others.emplace_back(q.int64(0), q.text(1));
      }
    }
    for (const auto& [pk, other_date] : others) {
      // A stored date that no longer parses cannot be: it was validated when stored.
      SOIQ_ASSIGN_OR_RETURN(const std::optional<double> other_age, age_years(birth, other_date));
      SOIQ_ASSIGN_OR_RETURN(Statement up, c.prepare(kUpdateStudyAgeSql));
      up.bind(1, pk);
      up.bind(2, other_age);
      SOIQ_RETURN_IF_ERROR(up.run());
    }
  }
  return keys;
}

}  // namespace soiq::db
