#pragma once
// Where soiqd keeps its records (--db): a SQLite file, the embedded default, or a PostgreSQL
// database that several soiqd replicas share (docs/SCALE_OUT.md).
//
//   PATH, sqlite:PATH               a SQLite file, made (with its folder) when missing
//   postgresql://…, postgres://…    a PostgreSQL connection URI as libpq reads it
//                                   (postgresql://soiq@db:5432/soiq?sslmode=require); the password
//                                   is best left to PGPASSWORD or ~/.pgpass, out of the process list
//
// Errors: INVALID_ARGUMENT for an empty location or another scheme (mysql://…), naming the forms
// soiqd takes; open_store returns the backend's own errors (an unreachable server is UNAVAILABLE).

#include <memory>
#include <string>

#include "core/base/status.h"
#include "db/sql/sql_store.h"
#include "db/store.h"

namespace soiq::server {

struct StoreLocation {
  enum class Kind { kSqlite, kPostgres } kind = Kind::kSqlite;
  std::string target;  // the SQLite file's path, or the PostgreSQL URI
};

Result<StoreLocation> parse_store_location(const std::string& db);

// The location as a log line may show it: a URI's password replaced by "***".
std::string redacted_store_location(const std::string& db);

struct StoreOpenOptions {
  int read_connections = 4;  // SQLite: reader connections
  int connections = 8;       // PostgreSQL: the pool's size
  // Only read the store, as it is (no migration, every write refused): soiq-admin verify beside a
  // running soiqd. A SQLite file must exist then.
  bool read_only = false;
};

Result<std::unique_ptr<db::Store>> open_store(const StoreLocation& where, const StoreOpenOptions& options);
// The same store with the SQL layer's own operations (copy, digests: store_admin.h).
Result<std::unique_ptr<db::SqlStore>> open_sql_store(const StoreLocation& where, const StoreOpenOptions& options);

}  // namespace soiq::server
