// SqliteStore's feature cache: put_cached_features and cached_features.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/sqlite_store_write_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_structure;

class SqliteStoreWriteCache : public testing::SqliteStoreWrite {};

TEST_F(SqliteStoreWriteCache, CachedFeaturesRoundTripManyKeysAndReplace) {
  auto a = store_->add_structure(new_structure("P1", "S1", "a"));
  ASSERT_TRUE(a.ok());
  const std::string sha = a->structure.surface.sha256;
  std::vector<CachedFeature> entries;
  std::vector<std::string> keys;
  for (int i = 0; i < 700; ++i) {  // more keys than one IN list holds
    keys.push_back(std::string("key") + std::to_string(i));
    entries.push_back({keys.back(), "mean|inside|", {double(i), 0.5}});
  }
  entries.push_back({"key3", "empty", {}});
  ASSERT_TRUE(store_->put_cached_features(sha, entries).ok());
  auto got = store_->cached_features(keys);
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  EXPECT_EQ(got->size(), 701u);
  ASSERT_TRUE(store_->put_cached_features(sha, {{"key5", "mean|inside|", {-1}}}).ok());
  auto one = store_->cached_features({"key5", "nope"});
  ASSERT_EQ(one->size(), 1u);
  EXPECT_EQ((*one)[0].value, std::vector<double>{-1});
  auto empty = store_->cached_features({"key3"});
  ASSERT_EQ(empty->size(), 2u);
  EXPECT_EQ((*empty)[0].entry, "empty");
  EXPECT_TRUE((*empty)[0].value.empty());
}

}  // namespace
}  // namespace soiq::db
