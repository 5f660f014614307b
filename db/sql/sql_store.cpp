// SqlStore's methods that dispatch or count; the others are in sql_store_*.cpp by record kind.
#include "db/sql/sql_store.h"

#include "db/sql/record_sql.h"

namespace soiq::db {

Result<Counts> SqlStore::counts() {
  Counts n;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement st, c.prepare(kCountsSql));
    SOIQ_ASSIGN_OR_RETURN(const bool row, st.step());
    if (!row) return internal_error("count query returned no row");
    n = Counts{st.int64(0), st.int64(1), st.int64(2), st.int64(3), st.int64(4),
               st.int64(5), st.int64(6), st.int64(7), {}};
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
  return kind == BlobKind::kImage ? image_blob(key) : surface_blob(key);
}

}  // namespace soiq::db
