#include "server/app/store_location.h"

#include <filesystem>
#include <system_error>

#include "db/postgres/pg_store.h"
#include "db/sqlite/sqlite_store.h"

namespace soiq::server {
namespace {

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

Result<StoreLocation> parse_store_location(const std::string& db) {
  if (db.empty()) return invalid_argument("--db must not be empty");
  if (starts_with(db, "postgresql://") || starts_with(db, "postgres://")) {
    return StoreLocation{StoreLocation::Kind::kPostgres, db};
  }
  if (starts_with(db, "sqlite:")) {
    const std::string path = db.substr(7);
    if (path.empty()) return invalid_argument("--db sqlite: needs a path after the colon (sqlite:var/soiq.db)");
    return StoreLocation{StoreLocation::Kind::kSqlite, path};
  }
  if (const size_t scheme = db.find("://"); scheme != std::string::npos) {
    return invalid_argument("--db '" + db.substr(0, scheme) +
                            "://' is not a store soiqd knows; give a SQLite file (PATH or sqlite:PATH) or a "
                            "PostgreSQL database (postgresql://USER@HOST:PORT/DATABASE)");
  }
  return StoreLocation{StoreLocation::Kind::kSqlite, db};
}

std::string redacted_store_location(const std::string& db) {
  // postgresql://user:password@host… : the password is between the first ':' after the scheme
  // and the '@' that ends the user information.
  const size_t scheme = db.find("://");
  if (scheme == std::string::npos) return db;
  const size_t start = scheme + 3;
  const size_t at = db.find('@', start);
  const size_t slash = db.find('/', start);
  if (at == std::string::npos || (slash != std::string::npos && slash < at)) return db;
  const size_t colon = db.find(':', start);
  if (colon == std::string::npos || colon > at) return db;
  return db.substr(0, colon + 1) + "***" + db.substr(at);
}

Result<std::unique_ptr<db::Store>> open_store(const StoreLocation& where, const StoreOpenOptions& options) {
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqlStore> store, open_sql_store(where, options));
  return std::unique_ptr<db::Store>(std::move(store));
}

Result<std::unique_ptr<db::SqlStore>> open_sql_store(const StoreLocation& where, const StoreOpenOptions& options) {
  if (where.kind == StoreLocation::Kind::kPostgres) {
    db::PgOptions pg;
    pg.connections = options.connections;
    pg.read_only = options.read_only;
    SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::PgStore> store, db::PgStore::open(where.target, pg));
    return std::unique_ptr<db::SqlStore>(std::move(store));
  }
  const std::filesystem::path dir = std::filesystem::path(where.target).parent_path();
  std::error_code ec;
  // A failure shows as the open's.
  if (!dir.empty() && !options.read_only) std::filesystem::create_directories(dir, ec);
  db::SqliteOptions sqlite;
  sqlite.read_connections = options.read_connections;
  sqlite.read_only = options.read_only;
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqliteStore> store, db::SqliteStore::open(where.target, sqlite));
  return std::unique_ptr<db::SqlStore>(std::move(store));
}

}  // namespace soiq::server
