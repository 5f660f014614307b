#pragma once
// The fixture of the Store tests typed over backends (tests/db/store_*_test.cpp): a fresh, empty
// store of the backend (store_backends.h). Derive a suite template from it
// (template <typename B> class StoreWriteSeries : public testing::StoreTest<B> {};): two fixture
// classes may not share one suite name in a binary. Typed tests reach the members through this->.
// The suites follow the store's roles: records (store_write_*, store_import_batch, store_stage1*,
// store_dicomweb_search, ...), features (store_write_cache, store_precompute) and replicas
// (store_stage2_work).

#include <gtest/gtest.h>

#include <memory>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/temp_store.h"

namespace soiq::db::testing {

template <typename Backend>
class StoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = Backend::open(dir_);
    ASSERT_NE(store_, nullptr);
  }
  Counts counts() {
    Result<Counts> c = store_->counts();
    EXPECT_TRUE(c.ok()) << c.status().to_string();
    return c.ok() ? *c : Counts{};
  }

  // The store by role (db/store.h): a suite of one role's contract reaches the store through its
  // role only, so the role's interface alone is what it holds to that contract.
  RecordStore& records() { return *store_; }
  FeatureStore& features() { return *store_; }
  ReplicaStore& replicas() { return *store_; }

  TempDir dir_;
  std::unique_ptr<Store> store_;
};

}  // namespace soiq::db::testing
