// SqliteStore's writes: structures, series, import batches, deletes. Each public method is one write transaction
// (SqliteStore::write), so any error leaves the database as it was.
#include <sqlite3.h>

#include <set>

#include "db/age_years.h"
#include "db/sqlite_records.h"
#include "db/sqlite_store.h"
#include "db/validate_records.h"

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

struct StudyKeys {
  int64_t patient_pk = 0;
  int64_t study_pk = 0;
};

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

constexpr char kDeleteStage1RowsSql[] = R"sql(
  DELETE FROM stage1_rows WHERE patient_pk = ?1)sql";

// modalities is the study's modality and its series', each followed by '/', after a '/': /MR/CT/.
constexpr char kInsertStage1RowsSql[] = R"sql(
  INSERT INTO stage1_rows(structure_id, patient_pk, patient_id, sex, birth_date, age_years, study_date,
                          modalities, description, name_lower, laterality)
  SELECT s.id, p.pk, p.patient_id, p.sex, p.birth_date, st.age_years, st.study_date,
         '/' || st.modality || '/' ||
           coalesce((SELECT group_concat(se.modality || '/', '') FROM series se WHERE se.study_pk = st.pk), ''),
         st.description, lower(s.name), s.laterality
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.pk = ?1)sql";

// Rewrites the stage-1 rows of every structure of the patient from the base tables. Called by
// each write that changes a structure, or a patient, study or series field stage 1 filters on;
// a patient has few structures, so rewriting them all is simpler than tracking which changed.
Status refresh_stage1_rows(Connection& c, int64_t patient_pk) {
  {
    SOIQ_ASSIGN_OR_RETURN(Statement del, c.prepare(kDeleteStage1RowsSql));
    del.bind(1, patient_pk);
    SOIQ_RETURN_IF_ERROR(del.run());
  }
  SOIQ_ASSIGN_OR_RETURN(Statement ins, c.prepare(kInsertStage1RowsSql));
  ins.bind(1, patient_pk);
  return ins.run();
}

constexpr char kDeleteOrphanSurfaceSql[] = R"sql(
  DELETE FROM surfaces
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM structures WHERE surface_sha256 = ?1))sql";

// Deletes the surface (and, by cascade, its cached features) when no structure refers to it.
Status delete_surface_if_orphan(Connection& c, const std::string& sha256) {
  SOIQ_ASSIGN_OR_RETURN(Statement del, c.prepare(kDeleteOrphanSurfaceSql));
  del.bind(1, sha256);
  return del.run();
}

constexpr char kDeleteOrphanImageSql[] = R"sql(
  DELETE FROM image_blobs
  WHERE sha256 = ?1 AND NOT EXISTS (SELECT 1 FROM series WHERE image_sha256 = ?1))sql";

Status delete_image_if_orphan(Connection& c, const std::string& sha256) {
  SOIQ_ASSIGN_OR_RETURN(Statement del, c.prepare(kDeleteOrphanImageSql));
  del.bind(1, sha256);
  return del.run();
}

constexpr char kStructureByIdSql[] = R"sql(
  WHERE s.id = ?1)sql";

Result<StructureRecord> structure_by_id(Connection& c, int64_t id) {
  SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(select_sql({kStructureColumns}, {kStructureFrom, kStructureByIdSql})));
  q.bind(1, id);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return not_found("structure " + std::to_string(id) + " not found");
  return read_structure(q, 0);
}

// Validates a structure or series before any write (the caller returns the error unchanged).
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

Status validate_new_series(const NewSeries& s) {
  SOIQ_RETURN_IF_ERROR(validate_patient(s.patient));
  SOIQ_RETURN_IF_ERROR(validate_study(s.study, s.patient.patient_id));
  if (s.series.series_uid.empty()) return invalid_argument("series_uid is empty");
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.series_uid, "series_uid", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.series.modality, "modality", kMaxIdBytes));
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

constexpr char kInsertSurfaceSql[] = R"sql(
  INSERT INTO surfaces(sha256, vertex_count, triangle_count, min_x, min_y, min_z, max_x, max_y, max_z, blob)
  VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)
  ON CONFLICT(sha256) DO NOTHING)sql";

constexpr char kStructureBySourceUidSql[] = R"sql(
  SELECT s.id, s.surface_sha256, st.patient_pk, p.patient_id
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE s.source_uid = ?1)sql";

constexpr char kUpdateStructureSql[] = R"sql(
  UPDATE structures
  SET study_pk = ?2, name = ?3, laterality = ?4, robust = ?5, surface_sha256 = ?6, source_series_uid = ?7
  WHERE id = ?1)sql";

// The lowest id: when copies already exist (stored before this rule), always the same one.
constexpr char kStructureWithSameContentSql[] = R"sql(
  SELECT id FROM structures
  WHERE study_pk = ?1 AND source_series_uid = ?2 AND name = ?3 AND surface_sha256 = ?4
  ORDER BY id
  LIMIT 1)sql";

constexpr char kInsertStructureSql[] = R"sql(
  INSERT INTO structures(study_pk, name, laterality, robust, surface_sha256, source_series_uid, source_uid)
  VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)
  RETURNING id)sql";

// The inserts of add_structure and put_series inside the caller's transaction.
Result<AddedStructure> insert_structure(Connection& c, const NewStructure& s) {
  AddedStructure out;
  SOIQ_ASSIGN_OR_RETURN(const StudyKeys keys, upsert_patient_and_study(c, s.patient, s.study));
  {
    SOIQ_ASSIGN_OR_RETURN(Statement ins, c.prepare(kInsertSurfaceSql));
    ins.bind(1, s.surface.sha256);
    ins.bind(2, s.surface.vertex_count);
    ins.bind(3, s.surface.triangle_count);
    for (int i = 0; i < 6; ++i) ins.bind(4 + i, s.surface.bounds_mm[i]);
    ins.bind_blob(10, s.surface_blob.data(), s.surface_blob.size());
    SOIQ_RETURN_IF_ERROR(ins.run());
    out.surface_already_stored = sqlite3_changes64(c.handle()) == 0;
  }
  // A re-imported structure (same source_uid) keeps its id; its old surface goes if orphaned.
  std::optional<int64_t> old_patient_pk;
  if (!s.source_uid.empty()) {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kStructureBySourceUidSql));
    q.bind(1, s.source_uid);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (row) {
      const int64_t id = q.int64(0);
      const std::string old_sha = q.text(1);
      old_patient_pk = q.int64(2);
      if (*old_patient_pk != keys.patient_pk) {
        return failed_precondition("structure " + std::to_string(id) + " (source '" + s.source_uid +
                                   "') belongs to patient '" + q.text(3) + "', not to '" + s.patient.patient_id +
                                   "': an import never moves a structure to another patient");
      }
      SOIQ_ASSIGN_OR_RETURN(Statement up, c.prepare(kUpdateStructureSql));
      up.bind(1, id);
      up.bind(2, keys.study_pk);
      up.bind(3, s.name);
      up.bind(4, s.laterality);
      up.bind(5, int64_t{s.robust});
      up.bind(6, s.surface.sha256);
      up.bind(7, s.source_series_uid);
      SOIQ_RETURN_IF_ERROR(up.run());
      if (old_sha != s.surface.sha256) SOIQ_RETURN_IF_ERROR(delete_surface_if_orphan(c, old_sha));
      out.replaced = true;
      SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, keys.patient_pk));
      if (*old_patient_pk != keys.patient_pk) SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, *old_patient_pk));
      SOIQ_ASSIGN_OR_RETURN(out.structure, structure_by_id(c, id));
      return out;
    }
  }
  if (s.same_content_is_same_structure) {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kStructureWithSameContentSql));
    q.bind(1, keys.study_pk);
    q.bind(2, s.source_series_uid);
    q.bind(3, s.name);
    q.bind(4, s.surface.sha256);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (row) {
      out.recognised = true;
      SOIQ_ASSIGN_OR_RETURN(out.structure, structure_by_id(c, q.int64(0)));
      return out;
    }
  }
  int64_t id = 0;
  {
    SOIQ_ASSIGN_OR_RETURN(Statement ins, c.prepare(kInsertStructureSql));
    ins.bind(1, keys.study_pk);
    ins.bind(2, s.name);
    ins.bind(3, s.laterality);
    ins.bind(4, int64_t{s.robust});
    ins.bind(5, s.surface.sha256);
    ins.bind(6, s.source_series_uid);
    ins.bind(7, s.source_uid);
    SOIQ_ASSIGN_OR_RETURN(const bool row, ins.step());
    if (!row) return internal_error("insert of structure '" + s.name + "' returned no id");
    id = ins.int64(0);
  }
  SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, keys.patient_pk));
  SOIQ_ASSIGN_OR_RETURN(out.structure, structure_by_id(c, id));
  return out;
}

constexpr char kInsertImageBlobSql[] = R"sql(
  INSERT INTO image_blobs(sha256, blob) VALUES (?1, ?2)
  ON CONFLICT(sha256) DO NOTHING)sql";

constexpr char kSeriesOwnerSql[] = R"sql(
  SELECT se.image_sha256, st.patient_pk, p.patient_id
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE se.series_uid = ?1)sql";

// An upsert keeps the series' pk stable when it is replaced.
constexpr char kUpsertSeriesSql[] = R"sql(
  INSERT INTO series(series_uid, study_pk, modality, origin_x, origin_y, origin_z, spacing_x, spacing_y, spacing_z,
                     dim_x, dim_y, dim_z, d00, d01, d02, d10, d11, d12, d20, d21, d22, image_sha256,
                     frame_of_reference_uid, sop_class_uid, slice_instance_uids)
  VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19, ?20, ?21, ?22,
          ?23, ?24, ?25)
  ON CONFLICT(series_uid) DO UPDATE SET
    study_pk = excluded.study_pk, modality = excluded.modality,
    origin_x = excluded.origin_x, origin_y = excluded.origin_y, origin_z = excluded.origin_z,
    spacing_x = excluded.spacing_x, spacing_y = excluded.spacing_y, spacing_z = excluded.spacing_z,
    dim_x = excluded.dim_x, dim_y = excluded.dim_y, dim_z = excluded.dim_z,
    d00 = excluded.d00, d01 = excluded.d01, d02 = excluded.d02,
    d10 = excluded.d10, d11 = excluded.d11, d12 = excluded.d12,
    d20 = excluded.d20, d21 = excluded.d21, d22 = excluded.d22,
    image_sha256 = excluded.image_sha256, frame_of_reference_uid = excluded.frame_of_reference_uid,
    sop_class_uid = excluded.sop_class_uid, slice_instance_uids = excluded.slice_instance_uids)sql";

Result<bool> insert_series(Connection& c, const NewSeries& s) {
  bool replaced = false;
  SOIQ_ASSIGN_OR_RETURN(const StudyKeys keys, upsert_patient_and_study(c, s.patient, s.study));
  {
    SOIQ_ASSIGN_OR_RETURN(Statement ins, c.prepare(kInsertImageBlobSql));
    ins.bind(1, s.series.sha256);
    ins.bind_blob(2, s.image_blob.data(), s.image_blob.size());
    SOIQ_RETURN_IF_ERROR(ins.run());
  }
  std::optional<std::string> old_sha;
  std::optional<int64_t> old_patient_pk;
  {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kSeriesOwnerSql));
    q.bind(1, s.series.series_uid);
    SOIQ_ASSIGN_OR_RETURN(replaced, q.step());
    if (replaced) {
      old_sha = q.text(0);
      old_patient_pk = q.int64(1);
      // A series UID is the image's identity: another patient's upload that names it is a mistake
      // (or an attack), never a reason to move the images.
      if (*old_patient_pk != keys.patient_pk) {
        return failed_precondition("series '" + s.series.series_uid + "' belongs to patient '" + q.text(2) +
                                   "', not to '" + s.patient.patient_id +
                                   "': an upload never moves a series to another patient");
      }
    }
  }
  {
    SOIQ_ASSIGN_OR_RETURN(Statement up, c.prepare(kUpsertSeriesSql));
    const ImageGeometry& g = s.series.geometry;
    up.bind(1, s.series.series_uid);
    up.bind(2, keys.study_pk);
    up.bind(3, s.series.modality);
    for (int a = 0; a < 3; ++a) {
      up.bind(4 + a, g.origin_mm[a]);
      up.bind(7 + a, g.spacing_mm[a]);
      up.bind(10 + a, g.dims[a]);
    }
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col) up.bind(13 + 3 * r + col, g.direction[r][col]);
    }
    up.bind(22, s.series.sha256);
    up.bind(23, s.series.frame_of_reference_uid);
    up.bind(24, s.series.sop_class_uid);
    up.bind(25, join_uid_list(s.series.slice_instance_uids));
    SOIQ_RETURN_IF_ERROR(up.run());
  }
  if (old_sha && *old_sha != s.series.sha256) SOIQ_RETURN_IF_ERROR(delete_image_if_orphan(c, *old_sha));
  // The series' modality counts for its study's structures; a series moved from another
  // patient's study changes that patient's rows too.
  SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, keys.patient_pk));
  if (old_patient_pk && *old_patient_pk != keys.patient_pk) {
    SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, *old_patient_pk));
  }
  return replaced;
}

}  // namespace

Result<AddedStructure> SqliteStore::add_structure(const NewStructure& s) {
  SOIQ_RETURN_IF_ERROR(validate_new_structure(s));
  AddedStructure out;
  SOIQ_RETURN_IF_ERROR(write([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(out, insert_structure(c, s));
    return ok_status();
  }));
  return out;
}

Result<bool> SqliteStore::put_series(const NewSeries& s) {
  SOIQ_RETURN_IF_ERROR(validate_new_series(s));
  bool replaced = false;
  SOIQ_RETURN_IF_ERROR(write([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(replaced, insert_series(c, s));
    return ok_status();
  }));
  return replaced;
}

Result<ImportedBatch> SqliteStore::import_batch(const ImportBatch& b) {
  for (const NewSeries& s : b.series) SOIQ_RETURN_IF_ERROR(validate_new_series(s));
  for (const NewStructure& s : b.structures) SOIQ_RETURN_IF_ERROR(validate_new_structure(s));
  ImportedBatch out;
  SOIQ_RETURN_IF_ERROR(write([&](Connection& c) -> Status {
    out = {};  // write() may run this again after ABORTED
    // Series first: a structure's study then already has its series' modalities for stage 1.
    for (const NewSeries& s : b.series) {
      SOIQ_ASSIGN_OR_RETURN(const bool replaced, insert_series(c, s));
      out.series_replaced.push_back(replaced);
    }
    for (const NewStructure& s : b.structures) {
      SOIQ_ASSIGN_OR_RETURN(AddedStructure added, insert_structure(c, s));
      out.structures.push_back(std::move(added));
    }
    return ok_status();
  }));
  return out;
}

namespace {

constexpr char kDeleteStructureSql[] = R"sql(
  DELETE FROM structures WHERE id = ?1
  RETURNING surface_sha256)sql";

}  // namespace

Result<int64_t> SqliteStore::delete_structure(int64_t id) {
  SOIQ_RETURN_IF_ERROR(write([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement del, c.prepare(kDeleteStructureSql));
    del.bind(1, id);
    SOIQ_ASSIGN_OR_RETURN(const bool row, del.step());
    if (!row) return not_found("structure " + std::to_string(id) + " not found");
    const std::string sha = del.text(0);
    SOIQ_RETURN_IF_ERROR(del.run());
    return delete_surface_if_orphan(c, sha);
  }));
  return int64_t{1};
}

namespace {

constexpr char kSurfacesOfPatientSql[] = R"sql(
  SELECT s.surface_sha256
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.patient_id = ?1)sql";

constexpr char kImagesOfPatientSql[] = R"sql(
  SELECT se.image_sha256
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE p.patient_id = ?1)sql";

// ON DELETE CASCADE takes the studies, their series and structures.
constexpr char kDeletePatientSql[] = R"sql(
  DELETE FROM patients WHERE patient_id = ?1)sql";

}  // namespace

Result<int64_t> SqliteStore::delete_patient(const std::string& patient_id) {
  int64_t deleted = 0;
  SOIQ_RETURN_IF_ERROR(write([&](Connection& c) -> Status {
    // The blobs the patient refers to, collected before the cascade removes the references.
    std::set<std::string> surfaces, images;
    {
      SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kSurfacesOfPatientSql));
      q.bind(1, patient_id);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        ++deleted;
        surfaces.insert(q.text(0));
      }
    }
    {
      SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare(kImagesOfPatientSql));
      q.bind(1, patient_id);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        images.insert(q.text(0));
      }
    }
    {
      SOIQ_ASSIGN_OR_RETURN(Statement del, c.prepare(kDeletePatientSql));
      del.bind(1, patient_id);
      SOIQ_RETURN_IF_ERROR(del.run());
      if (sqlite3_changes64(c.handle()) == 0) return not_found("patient '" + patient_id + "' not found");
    }
    for (const std::string& sha : surfaces) SOIQ_RETURN_IF_ERROR(delete_surface_if_orphan(c, sha));
    for (const std::string& sha : images) SOIQ_RETURN_IF_ERROR(delete_image_if_orphan(c, sha));
    return ok_status();
  }));
  return deleted;
}

}  // namespace soiq::db
