#pragma once
// The one adapter from SQLite result codes to soiq::Status (STYLE.md §3), keeping SQLite's text.

#include <string_view>

#include "core/base/status.h"

struct sqlite3;

namespace soiq::db {

// `what` says what we were doing ("insert structure"). The code follows store.h's contract:
//   SQLITE_BUSY, SQLITE_LOCKED          -> UNAVAILABLE (busy past the timeout; retry the call)
//   SQLITE_CORRUPT                      -> DATA_LOSS
//   SQLITE_NOTADB                       -> FAILED_PRECONDITION (the file is not a database)
//   SQLITE_FULL                         -> RESOURCE_EXHAUSTED (disk full)
//   SQLITE_CANTOPEN, SQLITE_READONLY,
//   SQLITE_PERM, SQLITE_AUTH            -> FAILED_PRECONDITION (path or permissions)
//   anything else (IOERR, CONSTRAINT…)  -> INTERNAL
// `db` may be null (then only sqlite3_errstr(rc) is quoted).
Status sqlite_status(sqlite3* db, int rc, std::string_view what);

}  // namespace soiq::db
