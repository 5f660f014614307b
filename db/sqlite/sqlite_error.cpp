#include "db/sqlite/sqlite_error.h"

#include <sqlite3.h>

#include <string>

namespace soiq::db {

Status sqlite_status(sqlite3* db, int rc, std::string_view what) {
  std::string message(what);
  message += ": ";
  // sqlite3_errmsg describes the most recent failure on this connection, which is this one;
  // errstr is the generic text of the code, useful when no connection exists.
  message += db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
  message += " (SQLite code " + std::to_string(rc) + ")";
  switch (rc & 0xff) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return {StatusCode::kUnavailable, message + "; the database is busy, retry"};
    case SQLITE_CORRUPT:
      return data_loss(message);
    case SQLITE_NOTADB:
    case SQLITE_CANTOPEN:
    case SQLITE_READONLY:
    case SQLITE_PERM:
    case SQLITE_AUTH:
      return failed_precondition(message);
    case SQLITE_FULL: {
      // The operator's next step is on that disk: say which file it is (soiqd may run several).
      const char* file = db != nullptr ? sqlite3_db_filename(db, "main") : nullptr;
      const std::string store = file != nullptr && *file != '\0' ? std::string(file) : "the SQLite store";
      return resource_exhausted(message + "; the disk of " + store +
                                " is full: free space there (or move the store), then retry");
    }
    default:
      return internal_error(message);
  }
}

}  // namespace soiq::db
