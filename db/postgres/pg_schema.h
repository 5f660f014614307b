#pragma once
// The PostgreSQL store's schema: the same tables, columns and indexes as the SQLite store's latest
// version (db/sqlite/schema_migrations.cpp), in PostgreSQL's types, versioned and forward-only.
// PostgreSQL's version 1 is SQLite's version 6: no PostgreSQL database existed before it, so
// SQLite's history before it (its re-encodings of blobs) has nothing to migrate here. Version 2
// makes every text column compare in byte order (collation "C"), as SQLite's do; version 5 is
// SQLite's version 9, every stored byte checked (db/sql/checksum_stored_bytes.h); version 7 is
// SQLite's version 11, the kept DICOM instances.
//
// pg_migrate runs each missing step in one transaction holding a transaction-level advisory lock,
// so replicas starting together on one database migrate it once: the others wait on the lock,
// then find the version current. The version is the one row of soiq_schema.
//
// Errors   FAILED_PRECONDITION  the database has a newer version than this soiqd knows (run a
//                               newer soiqd); any PostgreSQL failure as pg_error.h maps it.

#include "core/base/status.h"
#include "db/postgres/pg_connection.h"

namespace soiq::db {

int pg_latest_schema_version();
Status pg_migrate(PgConnection& c);
Result<int> pg_schema_version(PgConnection& c);
// For a store opened without migrating (read only): OK when the database holds a store of a
// schema version this code knows (older ones included); FAILED_PRECONDITION when it is newer, or
// holds none.
Status pg_check_schema_readable(PgConnection& c);

}  // namespace soiq::db
