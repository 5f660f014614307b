#pragma once
// The Store backends the shared store tests run on (store_conformance_test.cpp and the tests
// typed over backends): each opens a fresh, empty store that lives as long as the test's TempDir.
//   SqliteBackend    a SQLite file in the TempDir
//   PostgresBackend  a database of its own on a real PostgreSQL 15, one server per test process
//                    (tests/support/postgres_process.h), started when a test first needs it
// A backend that cannot open (no PostgreSQL installed, the server would not start) fails the test
// with the reason: `make test` installs everything, so a missing server is an error, not a skip.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <string>

#include "db/postgres/pg_connection.h"
#include "db/postgres/pg_store.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"
#include "tests/support/postgres_process.h"

namespace soiq::db::testing {

struct SqliteBackend {
  static constexpr const char* kName = "SQLite";
  static std::unique_ptr<Store> open(const TempDir& dir) { return open_store(dir.file("store.db")); }
};

// The conninfo of a new, empty database on the shared server; "" after a failed ADD_FAILURE.
inline std::string fresh_postgres_database() {
  std::string why;
  soiq::testing::PostgresProcess& server = soiq::testing::shared_postgres(why);
  if (!why.empty()) {
    ADD_FAILURE() << "PostgreSQL: " << why;
    return "";
  }
  const std::string name = soiq::testing::unique_postgres_database_name("store");
  why = soiq::testing::ensure_postgres_database(server, name);
  if (!why.empty()) {
    ADD_FAILURE() << "PostgreSQL: " << why;
    return "";
  }
  return server.conninfo(name);
}

struct PostgresBackend {
  static constexpr const char* kName = "PostgreSQL";
  static std::unique_ptr<Store> open(const TempDir&, PgOptions options = {}) {
    const std::string conninfo = fresh_postgres_database();
    if (conninfo.empty()) return nullptr;
    options.connections = 4;
    auto store = PgStore::open(conninfo, options);
    EXPECT_TRUE(store.ok()) << store.status().to_string();
    return store.ok() ? std::move(store).value() : nullptr;
  }
};

// For TYPED_TEST_SUITE(..., StoreBackends, StoreBackendNames): test names say the backend.
using StoreBackends = ::testing::Types<SqliteBackend, PostgresBackend>;
struct StoreBackendNames {
  template <typename Backend>
  static std::string GetName(int) {
    return Backend::kName;
  }
};

}  // namespace soiq::db::testing
