// SqlStore's feature cache: values are little-endian float64 arrays with a checksum
// (cached_value.h), keyed by (key, entry), checked as they are read.
#include <string_view>
#include <unordered_set>

#include "db/cached_value.h"
#include "db/sql/keyed_rows.h"
#include "db/sql/record_sql.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

// Every entry under any of the keys.
constexpr KeyedSql kCachedFeaturesSql{R"sql(
  SELECT key, entry, value
  FROM feature_cache
  WHERE key)sql",
                                      "ORDER BY key, entry"};

}  // namespace

Result<std::vector<CachedFeature>> SqlStore::cached_features(const std::vector<std::string>& keys,
                                                             const std::vector<std::string>& entries) {
  std::vector<CachedFeature> out;
  if (keys.empty()) return out;
  // Rows of other entries are stepped over without a copy: only their entry text is looked at.
  const std::unordered_set<std::string_view> wanted(entries.begin(), entries.end());
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    out.clear();
    return for_each_keyed_row(c, keys, kCachedFeaturesSql, [&](const SqlStatement& q) -> Status {
      const std::string_view entry = q.text_view(1);
      if (!wanted.empty() && !wanted.count(entry)) return ok_status();
      CachedFeature f{q.text(0), std::string(entry), {}};
      SOIQ_RETURN_IF_ERROR(set_cached_value(f, q.blob_view(2)));
      out.push_back(std::move(f));
      return ok_status();
    });
  }));
  return out;
}

namespace {

constexpr char kSurfaceExistsSql[] = R"sql(
  SELECT 1 FROM surfaces WHERE sha256 = ?1)sql";

constexpr char kUpsertCachedFeatureSql[] = R"sql(
  INSERT INTO feature_cache(key, entry, surface_sha256, value) VALUES (?1, ?2, ?3, ?4)
  ON CONFLICT(key, entry) DO UPDATE SET surface_sha256 = excluded.surface_sha256, value = excluded.value)sql";

}  // namespace

Result<bool> surface_exists(SqlSession& c, const std::string& sha256) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kSurfaceExistsSql));
  q.bind(1, sha256);
  return q.step();
}

Status SqlStore::upsert_cached_features(SqlSession& c, const std::vector<SurfaceFeatures>& batch) {
  for (const SurfaceFeatures& s : batch) {
    SOIQ_ASSIGN_OR_RETURN(const bool stored, surface_exists(c, s.surface_sha256));
    if (!stored) continue;
    for (const CachedFeature& f : s.entries) {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(kUpsertCachedFeatureSql));
      const std::string value = cached_value_bytes(f);  // bound blobs must outlive the step
      up.bind(1, f.key);
      up.bind(2, f.entry);
      up.bind(3, s.surface_sha256);
      up.bind_blob(4, value);
      SOIQ_RETURN_IF_ERROR(up.run());
    }
  }
  return ok_status();
}

Status SqlStore::put_cached_features(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) {
  SOIQ_RETURN_IF_ERROR(validate_cache_entries(surface_sha256, entries));
  return write([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(const bool stored, surface_exists(c, surface_sha256));
    // The surface may have been deleted while its features were computed: nothing to cache then.
    if (!stored) return not_found("surface " + surface_sha256 + " not found; its features are not cached");
    return upsert_cached_features(c, {{surface_sha256, entries}});
  });
}

Status SqlStore::put_cached_features(const std::vector<SurfaceFeatures>& batch) {
  for (const SurfaceFeatures& s : batch) SOIQ_RETURN_IF_ERROR(validate_cache_entries(s.surface_sha256, s.entries));
  if (batch.empty()) return ok_status();
  // The upsert decides by itself (ON CONFLICT), and a surface deleted meanwhile is skipped: no read
  // of this transaction must stay true at commit, so the queue's lighter unit serves (on
  // PostgreSQL, no serialization failures between replicas caching at once).
  return write_queue([&](SqlSession& c) { return upsert_cached_features(c, batch); });
}

}  // namespace soiq::db
