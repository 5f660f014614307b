#pragma once
// The schema step after which no stored byte goes unchecked (SQLite's version 9, PostgreSQL's
// version 5), written once on the SQL session (sql_session.h) for both backends, and run inside
// the migration's transaction:
//   - every surface blob of an older version (1 or 2, surface_blob.h) is re-encoded in version 3,
//     with its checksum, once it decodes to the sha256 it is stored under;
//   - every cached value stored without a checksum (cached_value.h) gets one.
// The sha256, counts and bounds describe the mesh, not its codec, and stay; so do the keys.
//
// A surface blob that does not decode, or decodes to another sha256, is damaged already: it is
// left as it is, since a checksum over it would make a wrong mesh look sound. soiqd then refuses
// it when it reads it (DATA_LOSS naming the structure: a blob without a checksum is checked
// against its sha256 there), soiq-admin verify lists it, and the migration still completes, so
// one damaged surface does not keep the whole store from opening. A cached value without a
// checksum has nothing to be checked against, and gets one as it is.
//
// Errors   the session's.
// Cost     one decode, hash and encode per surface blob of an older version, one pass over the
//          feature cache (a page of rows at a time) and a write per value without a checksum.

#include "core/base/status.h"
#include "db/sql/sql_session.h"

namespace soiq::db {

Status checksum_stored_bytes(SqlSession& c);

}  // namespace soiq::db
