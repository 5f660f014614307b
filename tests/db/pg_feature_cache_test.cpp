// The feature cache on a real PostgreSQL 15, with the SQLite store's meaning: many keys in one
// read, only the named entries, replace on write, a gone surface's entries skipped, nothing written
// for a malformed batch, and keys and entries with any characters read back exactly.
#include "db/postgres/pg_feature_cache.h"

#include <gtest/gtest.h>

#include "db/postgres/pg_schema.h"
#include "tests/db/pg_database.h"

namespace soiq::db {
namespace {

class PgFeatureCache : public PgTest {
 protected:
  void SetUp() override {
    PgTest::SetUp();
    auto c = connect();
    ASSERT_TRUE(c.ok());
    c_.emplace(std::move(*c));
    ASSERT_TRUE(pg_migrate(*c_).ok());
    for (const std::string& sha : {kA, kB}) {
      ASSERT_TRUE(
          c_->exec("INSERT INTO surfaces VALUES ($1, 4, 4, 0, 0, 0, 1, 1, 1, '\\x00')", {sha}, "add a surface").ok());
    }
  }
  std::vector<CachedFeature> read(const std::vector<std::string>& keys, const std::vector<std::string>& entries) {
    auto got = pg_cached_features(*c_, keys, entries);
    EXPECT_TRUE(got.ok()) << got.status().to_string();
    return got.ok() ? *got : std::vector<CachedFeature>{};
  }

  const std::string kA = std::string(64, 'a'), kB = std::string(64, 'b');
  std::optional<PgConnection> c_;
};

TEST_F(PgFeatureCache, ManyKeysRoundTripAndAReadTakesOnlyTheNamedEntries) {
  std::vector<CachedFeature> entries;
  std::vector<std::string> keys;
  for (int i = 0; i < 700; ++i) {
    keys.push_back("key" + std::to_string(i));
    entries.push_back({keys.back(), "mean|inside|", {double(i), 0.5}});
  }
  entries.push_back({"key3", "empty", {}});
  ASSERT_TRUE(pg_put_cached_features(*c_, {{kA, entries}}).ok());
  EXPECT_EQ(read(keys, {}).size(), 701u);
  ASSERT_TRUE(pg_put_cached_features(*c_, {{kA, {{"key5", "mean|inside|", {-1}}}}}).ok());
  const auto one = read({"key5", "nope"}, {});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].value, std::vector<double>{-1});
  const auto key3 = read({"key3"}, {});
  ASSERT_EQ(key3.size(), 2u);
  EXPECT_EQ(key3[0].entry, "empty");  // ordered by entry
  EXPECT_TRUE(key3[0].value.empty());
  const auto named = read({"key3", "key4"}, {"empty", "not cached"});
  ASSERT_EQ(named.size(), 1u);
  EXPECT_EQ(named[0].key, "key3");
}

TEST_F(PgFeatureCache, AGoneSurfaceIsSkippedAndAMalformedBatchWritesNothing) {
  const std::string gone(64, 'f');
  std::vector<SurfaceFeatures> batch = {{kA, {{"ka", "volume", {1}}}},
                                        {gone, {{"kg", "volume", {9}}}},
                                        {kB, {{"kb", "volume", {2}}, {"kb", "area", {3}}}}};
  ASSERT_TRUE(pg_put_cached_features(*c_, batch).ok());
  const auto got = read({"ka", "kb", "kg"}, {});
  EXPECT_EQ(got.size(), 3u);
  for (const CachedFeature& f : got) EXPECT_NE(f.key, "kg");

  batch[0].entries[0] = {"ka", "", {5}};
  EXPECT_EQ(pg_put_cached_features(*c_, batch).code(), StatusCode::kInvalidArgument);
  batch[0].entries[0] = {"ka", "volume", {5}};
  batch[2].surface_sha256 = "not a sha";
  EXPECT_EQ(pg_put_cached_features(*c_, batch).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(read({"ka"}, {})[0].value, std::vector<double>{1});  // unchanged
}

TEST_F(PgFeatureCache, AnyCharactersInKeysAndEntriesReadBackExactly) {
  const std::vector<std::string> odd = {"a,b", "{braces}", "quote\"d", "back\\slash", " spaced ", "NULL", "é ü 中"};
  std::vector<CachedFeature> entries;
  for (size_t i = 0; i < odd.size(); ++i) entries.push_back({odd[i], odd[(i + 1) % odd.size()], {double(i)}});
  ASSERT_TRUE(pg_put_cached_features(*c_, {{kA, entries}}).ok());
  for (const CachedFeature& f : entries) {
    const auto got = read({f.key}, {f.entry});
    ASSERT_EQ(got.size(), 1u) << f.key;
    EXPECT_EQ(got[0].key, f.key);
    EXPECT_EQ(got[0].entry, f.entry);
    EXPECT_EQ(got[0].value, f.value);
  }
}

TEST_F(PgFeatureCache, AnEntryGivenTwiceInOneBatchKeepsItsLastValue) {
  ASSERT_TRUE(pg_put_cached_features(*c_, {{kA, {{"k", "v", {1}}}}, {kB, {{"k", "v", {2}}}}}).ok());
  const auto got = read({"k"}, {});
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].value, std::vector<double>{2});
}

}  // namespace
}  // namespace soiq::db
