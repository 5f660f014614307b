// SqlStore's side of precompute (db/store.h): the durable queue, the stored default features and
// their copy in stage1_rows (schema version 5, schema_migrations.cpp).

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "db/sql/record_sql.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

// Queued again clears an old failure: the structure or its images changed, so it may succeed now.
constexpr char kQueueStructureSql[] = R"sql(
  INSERT INTO precompute_queue(structure_id) VALUES (?1)
  ON CONFLICT(structure_id) DO UPDATE SET failure = '')sql";

constexpr char kForgetStoredFeaturesSql[] = R"sql(
  DELETE FROM stored_features WHERE structure_id = ?1)sql";

// "WHERE true": SQLite needs a WHERE between an INSERT's SELECT and its ON CONFLICT.
constexpr char kQueueStudySql[] = R"sql(
  INSERT INTO precompute_queue(structure_id) SELECT id FROM structures WHERE study_pk = ?1 AND true
  ON CONFLICT(structure_id) DO UPDATE SET failure = '')sql";

constexpr char kQueueSql[] = R"sql(
  WHERE s.id IN (SELECT structure_id FROM precompute_queue WHERE failure = '' ORDER BY structure_id LIMIT ?1)
  ORDER BY s.id)sql";

// The structure's surface now, to tell whether the values still belong to it.
constexpr char kStructureSurfaceSql[] = R"sql(
  SELECT surface_sha256 FROM structures WHERE id = ?1)sql";

// The stored features' columns, written out once from stored_feature_names(): "a, b, …", or each
// as "a = <value(i)>, …" (i from 0).
std::string feature_columns() {
  std::string out;
  for (const std::string& n : stored_feature_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}
template <typename Value>
std::string feature_assignments(const Value& value) {
  std::string out;
  const std::vector<std::string>& names = stored_feature_names();
  for (size_t i = 0; i < names.size(); ++i) out += ", " + names[i] + " = " + value(i);
  return out;
}

// ?1 the structure, ?2 the definitions version, ?3 the precomputed set, then the values; replacing
// stored ones.
const std::string& store_features_sql() {
  static const std::string sql = [] {
    std::string values,
        replace = "definitions_version = excluded.definitions_version, precomputed_set = excluded.precomputed_set";
    for (size_t i = 0; i < stored_feature_names().size(); ++i) {
      values += ", ?" + std::to_string(i + 4);
      replace += ", " + stored_feature_names()[i] + " = excluded." + stored_feature_names()[i];
    }
    return "INSERT INTO stored_features(structure_id, definitions_version, precomputed_set, " + feature_columns() +
           ") VALUES (?1, ?2, ?3" + values + ") ON CONFLICT(structure_id) DO UPDATE SET " + replace;
  }();
  return sql;
}

// The same values in the structure's stage-1 row (rewriting the patient's rows would do too, but
// this is one row): ?1 the structure, then the values.
const std::string& stage1_features_sql() {
  static const std::string sql = "UPDATE stage1_rows SET features_stored = 1" +
                                 feature_assignments([](size_t i) { return "?" + std::to_string(i + 2); }) +
                                 " WHERE structure_id = ?1";
  return sql;
}

constexpr char kDequeueSql[] = R"sql(
  DELETE FROM precompute_queue WHERE structure_id = ?1)sql";

constexpr char kFailSql[] = R"sql(
  UPDATE precompute_queue SET failure = ?2 WHERE structure_id = ?1)sql";

// Stale values: their structures are queued again, then the values and their stage-1 copies go.
constexpr char kRequeueStaleSql[] = R"sql(
  INSERT INTO precompute_queue(structure_id)
  SELECT structure_id FROM stored_features WHERE definitions_version <> ?1 AND true
  ON CONFLICT(structure_id) DO UPDATE SET failure = '')sql";
// ?1 the definitions version that stays.
const std::string& unstore_stale_rows_sql() {
  static const std::string sql =
      "UPDATE stage1_rows SET features_stored = 0" + feature_assignments([](size_t) { return std::string("NULL"); }) +
      " WHERE structure_id IN (SELECT structure_id FROM stored_features WHERE definitions_version <> ?1)";
  return sql;
}
constexpr char kDeleteStaleSql[] = R"sql(
  DELETE FROM stored_features WHERE definitions_version <> ?1)sql";
// Values of this version but of a smaller set (?2) than soiqd computes now: queued again, and kept,
// since what they hold is right; the next precompute finds those in the feature cache.
constexpr char kRequeueSmallerSetSql[] = R"sql(
  INSERT INTO precompute_queue(structure_id)
  SELECT structure_id FROM stored_features WHERE definitions_version = ?1 AND precomputed_set < ?2
  ON CONFLICT(structure_id) DO UPDATE SET failure = '')sql";

}  // namespace

Status queue_precompute(SqlSession& c, int64_t structure_id, bool surface_changed) {
  if (surface_changed) {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement forget, c.prepare(kForgetStoredFeaturesSql));
    forget.bind(1, structure_id);
    SOIQ_RETURN_IF_ERROR(forget.run());
  }
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kQueueStructureSql));
  q.bind(1, structure_id);
  return q.run();
}

Status queue_precompute_of_study(SqlSession& c, int64_t study_pk) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kQueueStudySql));
  q.bind(1, study_pk);
  return q.run();
}

Result<std::vector<StructureRecord>> SqlStore::precompute_queue(int64_t limit) {
  if (limit < 1) return invalid_argument("precompute queue limit must be >= 1, got " + std::to_string(limit));
  std::vector<StructureRecord> out;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(select_sql({kStructureColumns}, {kStructureFrom, kQueueSql})));
    q.bind(1, limit);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      out.push_back(read_structure(q, 0));
    }
    return ok_status();
  }));
  return out;
}

namespace {

// One structure's part of put_precomputed, inside its transaction; its cache entries go into
// `cache` for one write of them all.
Status store_precomputed(SqlSession& c, const Precomputed& p, std::vector<SurfaceFeatures>& cache) {
  const size_t n = stored_feature_names().size();
  {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement now, c.prepare(kStructureSurfaceSql));
    now.bind(1, p.structure_id);
    SOIQ_ASSIGN_OR_RETURN(const bool found, now.step());
    // Deleted meanwhile, or given a new surface (and queued again by that write): these values
    // describe nothing stored.
    if (!found || now.text(0) != p.surface_sha256) return ok_status();
  }
  if (!p.failure.empty()) {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement fail, c.prepare(kFailSql));
    fail.bind(1, p.structure_id);
    fail.bind(2, p.failure.substr(0, kMaxPrecomputeFailureBytes));
    return fail.run();
  }
  cache.push_back({p.surface_sha256, p.cache_entries});
  // NaN is stored as NULL: neither satisfies any condition, as in stage 2 (server/app/query.h).
  auto bind_value = [&](SqlStatement& st, int index, size_t i) {
    const bool known = p.values[i] && !std::isnan(*p.values[i]);
    st.bind(index, known ? p.values[i] : std::nullopt);
  };
  SOIQ_ASSIGN_OR_RETURN(SqlStatement store, c.prepare(store_features_sql()));
  store.bind(1, p.structure_id);
  store.bind(2, int64_t{p.definitions_version});
  store.bind(3, int64_t(p.set));
  for (size_t i = 0; i < n; ++i) bind_value(store, int(i + 4), i);
  SOIQ_RETURN_IF_ERROR(store.run());
  SOIQ_ASSIGN_OR_RETURN(SqlStatement row, c.prepare(stage1_features_sql()));
  row.bind(1, p.structure_id);
  for (size_t i = 0; i < n; ++i) bind_value(row, int(i + 2), i);
  SOIQ_RETURN_IF_ERROR(row.run());
  SOIQ_ASSIGN_OR_RETURN(SqlStatement done, c.prepare(kDequeueSql));
  done.bind(1, p.structure_id);
  return done.run();
}

}  // namespace

Status SqlStore::put_precomputed(const std::vector<Precomputed>& batch) {
  for (const Precomputed& p : batch) SOIQ_RETURN_IF_ERROR(validate_precomputed(p));
  if (batch.empty()) return ok_status();
  return write([&](SqlSession& c) -> Status {
    std::vector<SurfaceFeatures> cache;
    for (const Precomputed& p : batch) SOIQ_RETURN_IF_ERROR(store_precomputed(c, p, cache));
    return upsert_cached_features(c, cache);
  });
}

Result<int64_t> SqlStore::requeue_precompute(int definitions_version, PrecomputedSet set) {
  int64_t requeued = 0;
  SOIQ_RETURN_IF_ERROR(write([&](SqlSession& c) -> Status {
    for (const std::string_view sql : {std::string_view(kRequeueStaleSql), std::string_view(unstore_stale_rows_sql()),
                                       std::string_view(kDeleteStaleSql)}) {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement st, c.prepare(sql));
      st.bind(1, int64_t{definitions_version});
      SOIQ_RETURN_IF_ERROR(st.run());
      requeued = st.changes();  // the last statement's: the values deleted
    }
    SOIQ_ASSIGN_OR_RETURN(SqlStatement smaller, c.prepare(kRequeueSmallerSetSql));
    smaller.bind(1, int64_t{definitions_version});
    smaller.bind(2, int64_t(set));
    SOIQ_RETURN_IF_ERROR(smaller.run());
    requeued += smaller.changes();
    return ok_status();
  }));
  return requeued;
}

}  // namespace soiq::db
