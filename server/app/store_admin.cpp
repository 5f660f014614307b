#include "server/app/store_admin.h"

#include "db/sqlite/sqlite_backup.h"

namespace soiq::server {

Result<std::vector<db::TableDigest>> migrate_store(const StoreLocation& from, const StoreLocation& to,
                                                   const std::function<void(const std::string&, int64_t)>& progress) {
  if (from.kind == to.kind && from.target == to.target) return invalid_argument("migrate needs two different stores");
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqlStore> source, open_sql_store(from, {}));
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqlStore> target, open_sql_store(to, {}));
  SOIQ_RETURN_IF_ERROR(source->copy_to(*target, progress));
  SOIQ_RETURN_IF_ERROR(target->after_bulk_load());
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::TableDigest> want, source->table_digests());
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::TableDigest> got, target->table_digests());
  for (size_t i = 0; i < want.size(); ++i) {
    if (i >= got.size() || got[i].rows != want[i].rows || got[i].sha256 != want[i].sha256) {
      return data_loss("table " + want[i].table + " differs after the copy (" + std::to_string(want[i].rows) +
                       " rows in the source, " + (i < got.size() ? std::to_string(got[i].rows) : "none") +
                       " in the target); do not use the target");
    }
  }
  return got;
}

Status backup_store(const StoreLocation& from, const std::string& to_path) {
  if (from.kind != StoreLocation::Kind::kSqlite) {
    return failed_precondition(
        "soiq-admin backup copies SQLite files; back a PostgreSQL database up with pg_dump --format=custom");
  }
  if (to_path.empty()) return invalid_argument("backup needs a target file (--to FILE)");
  return db::sqlite_backup(from.target, to_path);
}

}  // namespace soiq::server
