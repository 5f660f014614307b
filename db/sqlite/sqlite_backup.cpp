#include "db/sqlite/sqlite_backup.h"

#include <sqlite3.h>
#include <unistd.h>

#include <cstdio>

namespace soiq::db {
namespace {

struct Db {
  sqlite3* db = nullptr;
  ~Db() { sqlite3_close(db); }
};

}  // namespace

Status sqlite_backup(const std::string& from_path, const std::string& to_path) {
  Db from, to;
  // Read-only, and never created: a mistyped source is an error, not a new empty store.
  if (sqlite3_open_v2(from_path.c_str(), &from.db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    return failed_precondition("cannot open the SQLite store '" + from_path + "': " + sqlite3_errmsg(from.db));
  }
  sqlite3_busy_timeout(from.db, 5000);
  const std::string partial = to_path + ".partial";
  std::remove(partial.c_str());
  if (sqlite3_open(partial.c_str(), &to.db) != SQLITE_OK) {
    return failed_precondition("cannot write the backup '" + partial + "': " + sqlite3_errmsg(to.db));
  }
  sqlite3_backup* b = sqlite3_backup_init(to.db, "main", from.db, "main");
  if (b == nullptr) return failed_precondition(std::string("cannot start the backup: ") + sqlite3_errmsg(to.db));
  int rc = SQLITE_OK;
  // A few thousand pages per step, so a writer in soiqd waits at most one step for the lock.
  do {
    rc = sqlite3_backup_step(b, 4096);
    if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) sqlite3_sleep(20);
  } while (rc == SQLITE_OK || rc == SQLITE_BUSY || rc == SQLITE_LOCKED);
  sqlite3_backup_finish(b);
  if (rc != SQLITE_DONE) {
    std::remove(partial.c_str());
    if (rc == SQLITE_NOTADB) return failed_precondition("'" + from_path + "' is not a SQLite database");
    return Status(StatusCode::kUnavailable,
                  std::string("the backup of '") + from_path + "' failed: " + sqlite3_errstr(rc));
  }
  sqlite3_close(to.db);  // before the rename: the copy is whole on disk
  to.db = nullptr;
  if (std::rename(partial.c_str(), to_path.c_str()) != 0) {
    std::remove(partial.c_str());
    return failed_precondition("cannot rename the backup to '" + to_path + "'");
  }
  return ok_status();
}

}  // namespace soiq::db
