#pragma once
// The steps of the SQLite schema's migrations that SQL cannot say (schema_migrations.cpp): blobs
// re-encoded in a newer codec, inside the migration's transaction. Released steps: never edited.
//
// Input    a connection inside the migration's write transaction.
// Errors   versions 4 and 5: DATA_LOSS when a blob does not decode to its own sha256; the
//          connection's errors.
// Cost     one decode and encode per stored blob.

#include "core/base/status.h"
#include "db/sqlite/sqlite_connection.h"

namespace soiq::db {

// Version 4: each surface blob in the delta-planes codec, measured for the memory budget.
Status reencode_surface_blobs(Connection& c);
// Version 5: each image blob of version 1 (zlib) in the delta-planes codec.
Status reencode_image_blobs(Connection& c);
// Version 9: every stored byte checked: surface blobs in version 3, cached values with their
// checksum (db/sql/checksum_stored_bytes.h, the same step as PostgreSQL's).
Status sqlite_checksum_stored_bytes(Connection& c);

}  // namespace soiq::db
