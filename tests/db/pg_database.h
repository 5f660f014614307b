#pragma once
// Test support for the PostgreSQL store's tests: the tests' real PostgreSQL server
// (tests/support/postgres_process.h, shared_postgres) and a fresh database of its own for each test.

#include <gtest/gtest.h>

#include <string>

#include "db/postgres/pg_connection.h"
#include "tests/support/postgres_process.h"

namespace soiq::db {

class PgTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    server_ = &soiq::testing::shared_postgres(why);
    ASSERT_EQ(why, "");
    // A database of its own per test.
    database_ = soiq::testing::unique_postgres_database_name("t");
    ASSERT_EQ(soiq::testing::ensure_postgres_database(*server_, database_), "");
  }
  Result<PgConnection> connect() const { return PgConnection::open(conninfo()); }
  std::string conninfo() const { return server_->conninfo(database_); }

  soiq::testing::PostgresProcess* server_ = nullptr;
  std::string database_;
};

}  // namespace soiq::db
