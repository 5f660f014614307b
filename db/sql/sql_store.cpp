// SqlStore's methods that dispatch or count; the others are in sql_store_*.cpp by record kind.
#include "db/sql/sql_store.h"

#include <initializer_list>

#include "db/sql/record_sql.h"
#include "db/sql/sql_store_writes.h"

namespace soiq::db {

namespace {

// Reads the one row of `sql` into `fields`, column by column.
Status read_counts(SqlSession& c, const char* sql, std::initializer_list<int64_t*> fields) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement st, c.prepare(sql));
  SOIQ_ASSIGN_OR_RETURN(const bool row, st.step());
  if (!row) return internal_error("count query returned no row");
  int col = 0;
  for (int64_t* field : fields) *field = st.int64(col++);
  return ok_status();
}

}  // namespace

Result<Counts> SqlStore::counts() {
  Counts n;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    n = {};
    SOIQ_RETURN_IF_ERROR(read_counts(c, kCountsSql,
                                     {&n.patients, &n.studies, &n.series, &n.structures, &n.surfaces,
                                      &n.cached_features, &n.precompute_queued, &n.precompute_failed}));
    SOIQ_ASSIGN_OR_RETURN(const bool instances_kept, table_exists(c, "instances"));
    if (instances_kept)
      SOIQ_RETURN_IF_ERROR(read_counts(c, kInstanceCountsSql, {&n.instances, &n.instance_files, &n.instance_bytes}));
    SOIQ_ASSIGN_OR_RETURN(SqlStatement modalities, c.prepare(kSeriesModalitiesSql));
    for (;;) {
      SOIQ_ASSIGN_OR_RETURN(const bool more, modalities.step());
      if (!more) break;
      n.series_modalities.push_back(modalities.text(0));
    }
    return ok_status();
  }));
  return n;
}

Result<int64_t> SqlStore::remove(const Removal& r) {
  switch (r.kind) {
    case Removal::Kind::kStructure:
      return remove_structure(r.structure_id);
    case Removal::Kind::kPatient:
      return remove_patient(r.patient_id);
  }
  return invalid_argument("unknown kind of removal");
}

Result<std::string> SqlStore::get_blob(BlobKind kind, const std::string& key) {
  switch (kind) {
    case BlobKind::kImage:
      return image_blob(key);
    case BlobKind::kSurface:
      return surface_blob(key);
    case BlobKind::kInstanceFile:
      return instance_file(key);
  }
  return invalid_argument("unknown kind of blob");
}

}  // namespace soiq::db
