// A blob stored again under its sha256 (sql_store_writes.h, replace_differing_blob): the one
// stored is kept when it has the same bytes, and replaced when it has not. The new blob was just
// encoded from the mesh or image its sha256 names, so a stored one that differs is damaged or of
// an older version: uploading a structure's surface, or importing a series, again is how a
// damaged blob is repaired (soiq-admin verify says so).
#include <string>

#include "db/sql/sql_store_writes.h"

namespace soiq::db {

Result<StoredBlob> replace_differing_blob(SqlSession& c, std::string_view table, const std::string& sha256,
                                          std::string_view blob) {
  const std::string name(table);
  // The comparison runs in the database: the stored blob is not copied out.
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q,
                        c.prepare("SELECT CASE WHEN blob = ?2 THEN 1 ELSE 0 END FROM " + name + " WHERE sha256 = ?1"));
  q.bind(1, sha256);
  q.bind_blob(2, blob);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return StoredBlob::kAbsent;
  if (q.int64(0) == 1) return StoredBlob::kSame;
  SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare("UPDATE " + name + " SET blob = ?2 WHERE sha256 = ?1"));
  up.bind(1, sha256);
  up.bind_blob(2, blob);
  SOIQ_RETURN_IF_ERROR(up.run());
  return StoredBlob::kReplaced;
}

}  // namespace soiq::db
