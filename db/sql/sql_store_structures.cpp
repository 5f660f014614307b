// The structure half of SqlStore::import_batch: the surface blob stored once
// per sha256 (and stored again when the stored one is damaged), and a structure that is new, replaces the one with its
// source_uid, or is recognised as one already stored. One write transaction, so any error leaves the database as it
// was.

#include <optional>
#include <string>

#include "db/sql/record_sql.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

constexpr char kStructureByIdSql[] = R"sql(
  WHERE s.id = ?1)sql";

Result<StructureRecord> structure_by_id(SqlSession& c, int64_t id) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q,
                        c.prepare(select_sql({kStructureColumns}, {kStructureFrom, kStructureByIdSql})));
  q.bind(1, id);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return not_found("structure " + std::to_string(id) + " not found");
  return read_structure(q, 0);
}

constexpr char kInsertSurfaceSql[] = R"sql(
  INSERT INTO surfaces(sha256, vertex_count, triangle_count, min_x, min_y, min_z, max_x, max_y, max_z, blob)
  VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)
  ON CONFLICT(sha256) DO NOTHING)sql";

// Stores the surface blob unless one with its sha256 is there; true when it already was. A stored
// blob whose bytes differ is replaced (replace_differing_blob).
Result<bool> insert_surface(SqlSession& c, const NewStructure& s) {
  SOIQ_ASSIGN_OR_RETURN(const StoredBlob stored,
                        replace_differing_blob(c, "surfaces", s.surface.sha256, s.surface_blob));
  if (stored != StoredBlob::kAbsent) return true;
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, c.prepare(kInsertSurfaceSql));
  ins.bind(1, s.surface.sha256);
  ins.bind(2, s.surface.vertex_count);
  ins.bind(3, s.surface.triangle_count);
  for (int i = 0; i < 6; ++i) ins.bind(4 + i, s.surface.bounds_mm[i]);
  ins.bind_blob(10, s.surface_blob);
  SOIQ_RETURN_IF_ERROR(ins.run());
  return ins.changes() == 0;
}

constexpr char kStructureBySourceUidSql[] = R"sql(
  SELECT s.id, s.surface_sha256, st.patient_pk, p.patient_id, s.name
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE s.source_uid = ?1)sql";

constexpr char kUpdateStructureSql[] = R"sql(
  UPDATE structures
  SET study_pk = ?2, name = ?3, laterality = ?4, robust = ?5, surface_sha256 = ?6, source_series_uid = ?7,
      surface_area_bound_mm2 = ?8, surface_perimeter_bound_mm = ?9
  WHERE id = ?1)sql";

// A re-imported structure (same source_uid) keeps its id: the stored structure with s.source_uid,
// if any, is updated to `s` (its old surface goes if orphaned) and its id returned.
// FAILED_PRECONDITION when that structure belongs to another patient.
Result<std::optional<int64_t>> replace_by_source_uid(SqlSession& c, const NewStructure& s, const StudyKeys& keys) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kStructureBySourceUidSql));
  q.bind(1, s.source_uid);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return std::optional<int64_t>();
  const int64_t id = q.int64(0);
  const std::string old_sha = q.text(1);
  const int64_t old_patient_pk = q.int64(2);
  if (old_patient_pk != keys.patient_pk) {
    return failed_precondition("structure " + std::to_string(id) + " (source '" + s.source_uid +
                               "') belongs to patient '" + q.text(3) + "', not to '" + s.patient.patient_id +
                               "': an import never moves a structure to another patient");
  }
  if (!s.replace_other_content) {
    const std::string old_name = q.text(4);
    if (old_sha == s.surface.sha256 && old_name == s.name) return std::optional<int64_t>(id);  // the same: a no-op
    const size_t slash = s.source_uid.rfind('/');
    const std::string what =
        slash == std::string::npos
            ? "'" + s.source_uid + "'"
            : "ROI " + s.source_uid.substr(slash + 1) + " of DICOM object '" + s.source_uid.substr(0, slash) + "'";
    const std::string differs = old_sha != s.surface.sha256
                                    ? "another surface (sha256 " + old_sha.substr(0, 12) + "... stored, " +
                                          s.surface.sha256.substr(0, 12) + "... sent)"
                                    : "another name ('" + old_name + "' stored, '" + s.name + "' sent)";
    return Status(StatusCode::kAlreadyExists,
                  what + " is stored as structure " + std::to_string(id) + " with " + differs +
                      "; a DICOM UID names one content: send the object as stored, or replace it (soiq import "
                      "--replace)");
  }
  SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(kUpdateStructureSql));
  up.bind(1, id);
  up.bind(2, keys.study_pk);
  up.bind(3, s.name);
  up.bind(4, s.laterality);
  up.bind(5, int64_t{s.robust});
  up.bind(6, s.surface.sha256);
  up.bind(7, s.source_series_uid);
  up.bind(8, s.surface.area_bound_mm2);
  up.bind(9, s.surface.perimeter_bound_mm);
  SOIQ_RETURN_IF_ERROR(up.run());
  if (old_sha != s.surface.sha256) SOIQ_RETURN_IF_ERROR(delete_surface_if_orphan(c, old_sha));
  // A new surface means new values; the same surface (a re-import of the same contours) keeps them.
  SOIQ_RETURN_IF_ERROR(queue_precompute(c, id, old_sha != s.surface.sha256));
  SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, keys.patient_pk));
  if (old_patient_pk != keys.patient_pk) SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, old_patient_pk));
  return std::optional<int64_t>(id);
}

// The lowest id: when copies already exist (stored before this rule), always the same one.
constexpr char kStructureWithSameContentSql[] = R"sql(
  SELECT id FROM structures
  WHERE study_pk = ?1 AND source_series_uid = ?2 AND name = ?3 AND surface_sha256 = ?4
  ORDER BY id
  LIMIT 1)sql";

// The stored structure that `s` is by NewStructure::same_content_is_same_structure, if any.
Result<std::optional<int64_t>> structure_with_same_content(SqlSession& c, const NewStructure& s, int64_t study_pk) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kStructureWithSameContentSql));
  q.bind(1, study_pk);
  q.bind(2, s.source_series_uid);
  q.bind(3, s.name);
  q.bind(4, s.surface.sha256);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return std::optional<int64_t>();
  return std::optional<int64_t>(q.int64(0));
}

constexpr char kInsertStructureSql[] = R"sql(
  INSERT INTO structures(study_pk, name, laterality, robust, surface_sha256, source_series_uid, source_uid,
                         surface_area_bound_mm2, surface_perimeter_bound_mm)
  VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)
  RETURNING id)sql";

// Inserts `s` as a new structure of the study; returns its id.
Result<int64_t> insert_structure_row(SqlSession& c, const NewStructure& s, int64_t study_pk) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, c.prepare(kInsertStructureSql));
  ins.bind(1, study_pk);
  ins.bind(2, s.name);
  ins.bind(3, s.laterality);
  ins.bind(4, int64_t{s.robust});
  ins.bind(5, s.surface.sha256);
  ins.bind(6, s.source_series_uid);
  ins.bind(7, s.source_uid);
  ins.bind(8, s.surface.area_bound_mm2);
  ins.bind(9, s.surface.perimeter_bound_mm);
  SOIQ_ASSIGN_OR_RETURN(const bool row, ins.step());
  if (!row) return internal_error("insert of structure '" + s.name + "' returned no id");
  return ins.int64(0);
}

}  // namespace

Result<AddedStructure> insert_structure(SqlSession& c, const NewStructure& s) {
  AddedStructure out;
  SOIQ_ASSIGN_OR_RETURN(const StudyKeys keys, upsert_patient_and_study(c, s.patient, s.study));
  SOIQ_ASSIGN_OR_RETURN(out.surface_already_stored, insert_surface(c, s));
  if (!s.source_uid.empty()) {
    SOIQ_ASSIGN_OR_RETURN(const std::optional<int64_t> replaced, replace_by_source_uid(c, s, keys));
    if (replaced) {
      out.replaced = true;
      SOIQ_ASSIGN_OR_RETURN(out.structure, structure_by_id(c, *replaced));
      return out;
    }
  }
  if (s.same_content_is_same_structure) {
    SOIQ_ASSIGN_OR_RETURN(const std::optional<int64_t> same, structure_with_same_content(c, s, keys.study_pk));
    if (same) {
      out.recognised = true;
      SOIQ_ASSIGN_OR_RETURN(out.structure, structure_by_id(c, *same));
      return out;
    }
  }
  SOIQ_ASSIGN_OR_RETURN(const int64_t id, insert_structure_row(c, s, keys.study_pk));
  SOIQ_RETURN_IF_ERROR(queue_precompute(c, id, false));
  SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, keys.patient_pk));
  SOIQ_ASSIGN_OR_RETURN(out.structure, structure_by_id(c, id));
  return out;
}

}  // namespace soiq::db
