#include "db/postgres/pg_feature_cache.h"

#include <map>
#include <string_view>
#include <utility>

#include "db/cached_value.h"
#include "db/sql/record_sql.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

constexpr char kCachedSql[] = R"sql(
  SELECT key, entry, value FROM feature_cache
  WHERE key = ANY($1::text[]) AND (cardinality($2::text[]) = 0 OR entry = ANY($2::text[]))
  ORDER BY key, entry)sql";

// One row per entry from four parallel arrays; a surface that is gone keeps none of its rows.
constexpr char kUpsertSql[] = R"sql(
  INSERT INTO feature_cache(key, entry, surface_sha256, value)
  SELECT k, e, s, v FROM unnest($1::text[], $2::text[], $3::text[], $4::bytea[]) AS u(k, e, s, v)
  WHERE EXISTS (SELECT 1 FROM surfaces WHERE sha256 = u.s)
  ON CONFLICT (key, entry) DO UPDATE SET surface_sha256 = excluded.surface_sha256, value = excluded.value)sql";

}  // namespace

Result<std::vector<CachedFeature>> pg_cached_features(PgConnection& c, const std::vector<std::string>& keys,
                                                      const std::vector<std::string>& entries) {
  std::vector<CachedFeature> out;
  if (keys.empty()) return out;
  SOIQ_ASSIGN_OR_RETURN(PgResult r,
                        c.exec(kCachedSql, {array_literal(keys), array_literal(entries)}, "read cached features"));
  out.reserve(size_t(r.rows()));
  for (int i = 0; i < r.rows(); ++i) {
    CachedFeature f{r.text(i, 0), r.text(i, 1), {}};
    SOIQ_RETURN_IF_ERROR(set_cached_value(f, r.bytes(i, 2)));
    out.push_back(std::move(f));
  }
  return out;
}

Status pg_put_cached_features(PgConnection& c, const std::vector<SurfaceFeatures>& batch) {
  for (const SurfaceFeatures& s : batch) SOIQ_RETURN_IF_ERROR(validate_cache_entries(s.surface_sha256, s.entries));
  // One INSERT may not touch a row twice: an entry given twice keeps its last value, as the
  // row-by-row upserts of the SQLite store do.
  std::map<std::pair<std::string_view, std::string_view>, std::pair<const std::string*, const CachedFeature*>> rows;
  for (const SurfaceFeatures& s : batch) {
    for (const CachedFeature& f : s.entries) rows[{f.key, f.entry}] = {&s.surface_sha256, &f};
  }
  std::vector<std::string> keys, names, surfaces, values;
  for (const auto& [id, row] : rows) {
    const CachedFeature& f = *row.second;
    keys.push_back(f.key);
    names.push_back(f.entry);
    surfaces.push_back(*row.first);
    values.push_back(pg_bytea_hex(cached_value_bytes(f)));
  }
  if (keys.empty()) return ok_status();
  return c
      .exec(kUpsertSql, {array_literal(keys), array_literal(names), array_literal(surfaces), array_literal(values)},
            "store cached features")
      .status();
}

}  // namespace soiq::db
