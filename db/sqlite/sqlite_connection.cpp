#include "db/sqlite/sqlite_connection.h"

#include <sqlite3.h>

#include "db/sqlite/sqlite_error.h"

namespace soiq::db {
namespace {

// Dynamic SQL (stage-1 filters, list filters) has a bounded number of shapes, but bound it anyway;
// beyond this, statements are prepared for one use and finalized.
constexpr size_t kMaxCachedStatements = 128;

}  // namespace

Result<std::unique_ptr<Connection>> Connection::open(const std::string& path, int busy_timeout_ms, int cache_mib,
                                                     ConnectionRole role) {
  const int flags =
      SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX | (role == ConnectionRole::kWriter ? SQLITE_OPEN_CREATE : 0);
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &db, flags, nullptr);
  if (rc != SQLITE_OK) {
    Status s = sqlite_status(db, rc, "cannot open database '" + path + "'");
    sqlite3_close_v2(db);  // sqlite3_open_v2 allocates a handle even when it fails
    return s;
  }
  std::unique_ptr<Connection> c(new Connection(db, path));
  sqlite3_extended_result_codes(db, 1);
  sqlite3_busy_timeout(db, busy_timeout_ms);
  // SQLite reads the file lazily: the first statement that touches it is where a file that is not
  // a database shows up, so its error names the path.
  // A negative cache_size is in KiB.
  std::string pragmas = "PRAGMA foreign_keys=ON; PRAGMA synchronous=FULL; PRAGMA cache_size=-" +
                        std::to_string(int64_t{cache_mib} * 1024) + ";";
  if (role == ConnectionRole::kWriter) {
    pragmas = "PRAGMA journal_mode=WAL; " + pragmas;
  } else {
    pragmas += " PRAGMA query_only=ON;";
  }
  char* error = nullptr;
  const int prc = sqlite3_exec(db, pragmas.c_str(), nullptr, nullptr, &error);
  sqlite3_free(error);
  if (prc != SQLITE_OK) {
    return sqlite_status(db, prc, "'" + path + "' is not a usable SQLite database");
  }
  // journal_mode reports the mode it ended up in rather than failing (e.g. on a file system
  // without shared memory); WAL is a requirement, so check.
  if (role == ConnectionRole::kWriter) {
    SOIQ_ASSIGN_OR_RETURN(Statement mode, c->prepare("PRAGMA journal_mode"));
    SOIQ_ASSIGN_OR_RETURN(const bool row, mode.step());
    if (!row || mode.text(0) != "wal") {
      return failed_precondition("database '" + path + "' cannot use WAL journal mode (got '" +
                                 (row ? mode.text(0) : std::string()) + "'); put it on a local file system");
    }
  }
  return c;
}

Connection::~Connection() {
  for (auto& [sql, cached] : cache_) sqlite3_finalize(cached.stmt);
  sqlite3_close_v2(db_);
}

Result<Statement> Connection::prepare(std::string_view sql) {
  auto it = cache_.find(sql);
  if (it != cache_.end() && !it->second.in_use) {
    it->second.in_use = true;
    return Statement(db_, it->second.stmt, /*owned=*/false, &it->second.in_use);
  }
  sqlite3_stmt* stmt = nullptr;
  const bool cache = it == cache_.end() && cache_.size() < kMaxCachedStatements;
  const int rc =
      sqlite3_prepare_v3(db_, sql.data(), int(sql.size()), cache ? SQLITE_PREPARE_PERSISTENT : 0, &stmt, nullptr);
  if (rc != SQLITE_OK) return sqlite_status(db_, rc, "prepare " + std::string(sql));
  if (!cache) return Statement(db_, stmt, /*owned=*/true, nullptr);
  auto pos = cache_.emplace(std::string(sql), CachedStatement{stmt, true}).first;
  return Statement(db_, stmt, /*owned=*/false, &pos->second.in_use);
}

Status Connection::exec(const std::string& sql) {
  char* error = nullptr;
  const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error);
  sqlite3_free(error);  // sqlite3_errmsg has the same text
  if (rc != SQLITE_OK) return sqlite_status(db_, rc, "run " + sql);
  return ok_status();
}

Status run_transaction(Connection& c, TransactionKind kind, const std::function<Status()>& fn) {
  SOIQ_RETURN_IF_ERROR(c.exec(kind == TransactionKind::kWrite ? "BEGIN IMMEDIATE" : "BEGIN"));
  Status s = fn();
  if (s.ok()) {
    s = c.exec("COMMIT");
    if (s.ok()) return s;
  }
  // Some errors (SQLITE_FULL, IOERR…) roll the transaction back already; rolling back again
  // would fail, so only roll back one that is still open.
  if (!sqlite3_get_autocommit(c.handle())) (void)c.exec("ROLLBACK");
  return s;
}

}  // namespace soiq::db
