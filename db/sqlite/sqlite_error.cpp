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
    case SQLITE_FULL:
      return resource_exhausted(message);
    default:
      return internal_error(message);
  }
}

}  // namespace soiq::db
