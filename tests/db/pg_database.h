#pragma once
// Test support for the PostgreSQL store's tests: one real PostgreSQL server per test suite
// (tests/support/postgres_process.h) and a fresh database of its own for each test.

#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "db/postgres/pg_connection.h"
#include "tests/support/postgres_process.h"

namespace soiq::db {

class PgTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ = new soiq::testing::PostgresProcess;
    why_ = server_->start();
  }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
  }
  void SetUp() override {
    ASSERT_EQ(why_, "");
    // A database of its own per test.
    static std::atomic<int> next{0};
    database_ = "t" + std::to_string(next++);
    auto admin = PgConnection::open(server_->conninfo("postgres"));
    ASSERT_TRUE(admin.ok()) << admin.status().to_string();
    ASSERT_TRUE(admin->run("CREATE DATABASE " + database_, "create a test database").ok());
  }
  Result<PgConnection> connect() const { return PgConnection::open(conninfo()); }
  std::string conninfo() const { return server_->conninfo(database_); }

  inline static soiq::testing::PostgresProcess* server_ = nullptr;
  inline static std::string why_;
  std::string database_;
};

}  // namespace soiq::db
