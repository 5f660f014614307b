#pragma once
// What soiq-admin does to stores, on the locations soiqd takes (store_location.h):
//   migrate_store  copies every record from one store into an empty one of either backend
//                  (SQLite -> PostgreSQL to scale out, and back), keys included, then compares the
//                  two table by table (rows and a digest of their bytes): any difference is
//                  DATA_LOSS naming the table, and the copy is not to be trusted.
//   backup_store   a consistent copy of a live SQLite file (db/sqlite/sqlite_backup.h); for
//                  PostgreSQL use pg_dump (docs/SCALE_OUT.md), which this refuses to imitate.
// Errors: the stores' own; FAILED_PRECONDITION for a target that holds records, or a backup of
// PostgreSQL.

#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/sql/sql_store.h"
#include "server/app/store_location.h"

namespace soiq::server {

Result<std::vector<db::TableDigest>> migrate_store(const StoreLocation& from, const StoreLocation& to,
                                                   const std::function<void(const std::string&, int64_t)>& progress);

Status backup_store(const StoreLocation& from, const std::string& to_path);

}  // namespace soiq::server
