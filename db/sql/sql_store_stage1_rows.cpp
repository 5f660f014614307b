// stage1_rows, the narrow table stage 1 reads (schema_migrations.cpp), kept in step with the
// base tables by every write that changes what it copies (refresh_stage1_rows,
// sql_store_writes.h), inside that write's transaction.
#include <string>

#include "db/sql/sql_store_writes.h"

namespace soiq::db {
namespace {

constexpr char kDeleteStage1RowsSql[] = R"sql(
  DELETE FROM stage1_rows WHERE patient_pk = ?1)sql";

// modalities is the study's modality and its series', each followed by '/', after a '/': /MR/CT/
// (%s: the dialect's string aggregate). The stored features are copied from stored_features (the
// values of precompute, db/store.h).
constexpr char kInsertStage1RowsSql[] = R"sql(
  INSERT INTO stage1_rows(structure_id, patient_pk, patient_id, sex, birth_date, age_years, study_date,
                          modalities, description, name_lower, laterality, features_stored,
                          voxel_volume_mm3, surface_area_mm2, sphericity, elongation, flatness,
                          maximum_3d_diameter_mm)
  SELECT s.id, p.pk, p.patient_id, p.sex, p.birth_date, st.age_years, st.study_date,
         '/' || st.modality || '/' ||
           coalesce((SELECT %s(se.modality || '/', '') FROM series se WHERE se.study_pk = st.pk), ''),
         st.description, lower(s.name), s.laterality, CASE WHEN f.structure_id IS NULL THEN 0 ELSE 1 END,
         f.voxel_volume_mm3, f.surface_area_mm2, f.sphericity, f.elongation, f.flatness, f.maximum_3d_diameter_mm
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  LEFT JOIN stored_features f ON f.structure_id = s.id
  WHERE p.pk = ?1)sql";

const std::string& insert_stage1_rows_sql(SqlDialect dialect) {
  auto with = [](const char* aggregate) {
    std::string sql = kInsertStage1RowsSql;
    return sql.replace(sql.find("%s"), 2, aggregate);
  };
  static const std::string sqlite = with("group_concat"), postgres = with("string_agg");
  return dialect == SqlDialect::kSqlite ? sqlite : postgres;
}

}  // namespace

// Rewrites the stage-1 rows of every structure of the patient from the base tables. Called by
// each write that changes a structure, or a patient, study or series field stage 1 filters on;
// a patient has few structures, so rewriting them all is simpler than tracking which changed.
Status refresh_stage1_rows(SqlSession& c, int64_t patient_pk) {
  {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeleteStage1RowsSql));
    del.bind(1, patient_pk);
    SOIQ_RETURN_IF_ERROR(del.run());
  }
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, c.prepare(insert_stage1_rows_sql(c.dialect())));
  ins.bind(1, patient_pk);
  return ins.run();
}

}  // namespace soiq::db
