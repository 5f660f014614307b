#pragma once
// The versioned schema of the SQLite store: PRAGMA user_version is the number of migration steps
// applied; steps only go forward, each in its own transaction (schema_migrations.cpp lists them).

#include "core/base/status.h"
#include "db/sqlite/sqlite_connection.h"

namespace soiq::db {

// The schema version this code writes and reads.
int latest_schema_version();

// Brings the database on `c` (the writer) up to latest_schema_version(): an empty file gets the
// whole schema. FAILED_PRECONDITION when the database is newer than this code (both versions in the
// message); the error of the failing step otherwise, with the database left at the last good step.
Status migrate_schema(Connection& c);

// PRAGMA user_version of the database on `c`.
Result<int> schema_version(Connection& c);

// For a store opened without migrating (read only): OK when the database on `c` holds a store of
// a schema version this code knows (up to latest_schema_version(), older ones included);
// FAILED_PRECONDITION naming the path when it is newer (both versions) or holds none (version 0).
Status check_schema_readable(Connection& c);

}  // namespace soiq::db
