#pragma once
// A store of each backend with raw SQL beside it, as another program, an older soiqd or a failing
// disk would touch it: for the tests of what soiq does with stored bytes it did not write (damaged
// blobs and values, older encodings), on the real engines.
//   RawSqlite    a SQLite file in the test's TempDir
//   RawPostgres  a fresh database on the shared PostgreSQL server (store_backends.h)
// Each: `location` (what soiqd's --db takes), open() (migrated, or read only: as it is), run(sql,
// bytes, texts) with ?1 bound to `bytes` as a blob and ?2, ?3, … to `texts` (an error fails the
// test), and set_schema_version(v), with kBeforeChecksums its schema version before every stored
// byte had a checksum. Going back before kInstances drops the tables that version added (the kept
// DICOM instances), and before kWindows the columns that version added (the series' DICOM window),
// so that migrating forward again adds them as it did.

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "db/postgres/pg_connection.h"
#include "db/postgres/pg_session.h"
#include "db/postgres/pg_store.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/store_backends.h"

namespace soiq::db::testing {

template <typename Raw>
void drop_instances(const Raw& raw) {
  raw.run("DROP TABLE instances");
  raw.run("DROP TABLE instance_files");
}

template <typename Raw>
void drop_precomputed_set(const Raw& raw) {
  raw.run("ALTER TABLE stored_features DROP COLUMN precomputed_set");
}

template <typename Raw>
void drop_slice_positions(const Raw& raw) {
  raw.run("ALTER TABLE series DROP COLUMN slice_positions");
}

template <typename Raw>
void drop_windows(const Raw& raw) {
  raw.run("ALTER TABLE series DROP COLUMN window_center");
  raw.run("ALTER TABLE series DROP COLUMN window_width");
}

struct RawSqlite {
  static constexpr const char* kName = "SQLite";
  static constexpr int kBeforeChecksums = 8;
  static constexpr int kWindows = 10;
  static constexpr int kInstances = 11;
  static constexpr int kSlicePositions = 12;
  static constexpr int kPrecomputedSet = 13;
  explicit RawSqlite(const TempDir& dir) : location(dir.file("store.db")) {}

  std::unique_ptr<SqlStore> open(bool read_only = false) const {
    SqliteOptions options;
    options.read_only = read_only;
    auto store = SqliteStore::open(location, options);
    EXPECT_TRUE(store.ok()) << store.status().to_string();
    return store.ok() ? std::move(store).value() : nullptr;
  }

  void run(const std::string& sql, std::string_view bytes = {}, const std::vector<std::string>& texts = {}) const {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(location.c_str(), &db), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
    if (sqlite3_bind_parameter_count(st) >= 1)
      sqlite3_bind_blob(st, 1, bytes.data(), int(bytes.size()), SQLITE_TRANSIENT);
    for (size_t i = 0; i < texts.size(); ++i)
      sqlite3_bind_text(st, int(i + 2), texts[i].c_str(), int(texts[i].size()), SQLITE_TRANSIENT);
    int rc = SQLITE_ROW;
    while (rc == SQLITE_ROW) rc = sqlite3_step(st);
    EXPECT_EQ(rc, SQLITE_DONE) << sqlite3_errmsg(db) << " in " << sql;
    sqlite3_finalize(st);
    sqlite3_close(db);
  }

  void set_schema_version(int v) const {
    if (v < kPrecomputedSet) drop_precomputed_set(*this);
    if (v < kSlicePositions) drop_slice_positions(*this);
    if (v < kInstances) drop_instances(*this);
    if (v < kWindows) drop_windows(*this);
    run("PRAGMA user_version = " + std::to_string(v));
  }

  std::string location;
};

struct RawPostgres {
  static constexpr const char* kName = "PostgreSQL";
  static constexpr int kBeforeChecksums = 4;
  static constexpr int kWindows = 6;
  static constexpr int kInstances = 7;
  static constexpr int kSlicePositions = 8;
  static constexpr int kPrecomputedSet = 9;
  explicit RawPostgres(const TempDir&) : location(fresh_postgres_database()) {}

  std::unique_ptr<SqlStore> open(bool read_only = false) const {
    PgOptions options;
    options.connections = 2;
    options.read_only = read_only;
    auto store = PgStore::open(location, options);
    EXPECT_TRUE(store.ok()) << store.status().to_string();
    return store.ok() ? std::move(store).value() : nullptr;
  }

  void run(const std::string& sql, std::string_view bytes = {}, const std::vector<std::string>& texts = {}) const {
    auto c = PgConnection::open(location);
    ASSERT_TRUE(c.ok()) << c.status().to_string();
    const PgNumberedSql numbered = pg_numbered_parameters(sql);
    std::vector<PgParam> params;
    for (size_t n = 1; n < numbered.numbers.size(); ++n) {
      if (numbered.numbers[n] == 0) continue;
      params.push_back(n == 1 ? pg_binary_param(bytes) : PgParam(texts.at(n - 2)));
    }
    auto done = c->exec(numbered.sql, params, "a test's raw SQL");
    EXPECT_TRUE(done.ok()) << done.status().to_string() << " in " << sql;
  }

  void set_schema_version(int v) const {
    if (v < kPrecomputedSet) drop_precomputed_set(*this);
    if (v < kSlicePositions) drop_slice_positions(*this);
    if (v < kInstances) drop_instances(*this);
    if (v < kWindows) drop_windows(*this);
    run("UPDATE soiq_schema SET version = " + std::to_string(v));
  }

  std::string location;
};

using RawBackends = ::testing::Types<RawSqlite, RawPostgres>;

}  // namespace soiq::db::testing
