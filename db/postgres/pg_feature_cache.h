#pragma once
// The feature cache on PostgreSQL, with the Store's meaning (db/store.h: cached_features,
// put_cached_features), for the PostgreSQL store.
//
// pg_cached_features      the entries under `keys` (only those named in `entries`, or all when it
//                         is empty), ordered by key then entry; one statement for all the keys.
// pg_put_cached_features  every surface's entries in one statement, inserted or replaced; the
//                         entries of a surface that is gone (deleted meanwhile) are skipped, as on
//                         SQLite. Run it inside the caller's transaction.
// Errors   INVALID_ARGUMENT for a malformed sha256 or an empty key or entry (nothing written);
//          DATA_LOSS for a stored value whose checksum differs (cached_value.h); PostgreSQL's as
//          pg_error.h.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/postgres/pg_connection.h"
#include "db/store.h"

namespace soiq::db {

Result<std::vector<CachedFeature>> pg_cached_features(PgConnection& c, const std::vector<std::string>& keys,
                                                      const std::vector<std::string>& entries);
Status pg_put_cached_features(PgConnection& c, const std::vector<SurfaceFeatures>& batch);

}  // namespace soiq::db
