#pragma once
// The fixture of the SqliteStore write tests (tests/db/sqlite_store_write_*_test.cpp): a fresh store
// in a temporary directory. Derive a suite from it (class SqliteStoreWriteSeries : public
// testing::SqliteStoreWrite {}): two fixture classes may not share one suite name in a binary.

#include <gtest/gtest.h>

#include <memory>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"

namespace soiq::db::testing {

class SqliteStoreWrite : public ::testing::Test {
 protected:
  void SetUp() override { store_ = open_store(dir_.file("store.db")); }
  Counts counts() { return *store_->counts(); }

  TempDir dir_;
  std::unique_ptr<SqliteStore> store_;
};

}  // namespace soiq::db::testing
