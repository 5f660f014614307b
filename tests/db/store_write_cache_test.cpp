// The Store's feature cache, on every backend: put_cached_features and cached_features.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_structure;

template <typename Backend>
class StoreWriteCache : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreWriteCache, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreWriteCache, CachedFeaturesRoundTripManyKeysAndReplace) {
  auto a = this->store_->add_structure(new_structure("P1", "S1", "a"));
  ASSERT_TRUE(a.ok());
  const std::string sha = a->structure.surface.sha256;
  std::vector<CachedFeature> entries;
  std::vector<std::string> keys;
  for (int i = 0; i < 700; ++i) {  // more keys than one IN list holds
    keys.push_back(std::string("key") + std::to_string(i));
    entries.push_back({keys.back(), "mean|inside|", {double(i), 0.5}});
  }
  entries.push_back({"key3", "empty", {}});
  // Characters an array literal must quote or escape (PostgreSQL reads every key as one).
  keys.push_back(R"(odd "key" \ {a,b} NULL)");
  entries.push_back({keys.back(), R"(entry "with" \ {quotes})", {7}});
  ASSERT_TRUE(this->features().put_cached_features(sha, entries).ok());
  auto got = this->features().cached_features(keys);
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  EXPECT_EQ(got->size(), 702u);
  auto odd = this->features().cached_features({keys.back()}, {entries.back().entry});
  ASSERT_TRUE(odd.ok()) << odd.status().to_string();
  ASSERT_EQ(odd->size(), 1u);
  EXPECT_EQ((*odd)[0].key, keys.back());
  EXPECT_EQ((*odd)[0].value, std::vector<double>{7});
  ASSERT_TRUE(this->features().put_cached_features(sha, {{"key5", "mean|inside|", {-1}}}).ok());
  auto one = this->features().cached_features({"key5", "nope"});
  ASSERT_EQ(one->size(), 1u);
  EXPECT_EQ((*one)[0].value, std::vector<double>{-1});
  auto empty = this->features().cached_features({"key3"});
  ASSERT_EQ(empty->size(), 2u);
  EXPECT_EQ((*empty)[0].entry, "empty");
  EXPECT_TRUE((*empty)[0].value.empty());
}

// A query reads only the entries its plans want; an empty list reads every one.
TYPED_TEST(StoreWriteCache, CachedFeaturesReadOnlyTheNamedEntries) {
  auto a = this->store_->add_structure(new_structure("P1", "S1", "a"));
  ASSERT_TRUE(a.ok());
  const std::string sha = a->structure.surface.sha256;
  ASSERT_TRUE(this->store_
                  ->put_cached_features(sha, {{"k1", "volume", {1}},
                                              {"k1", "area", {2}},
                                              {"k1", "mean|inside|x", {3, 4}},
                                              {"k2", "volume", {5}},
                                              {"k2", "area", {6}}})
                  .ok());
  auto some = this->features().cached_features({"k1", "k2"}, {"volume", "mean|inside|x", "not cached"});
  ASSERT_TRUE(some.ok()) << some.status().to_string();
  std::vector<std::string> got;
  for (const CachedFeature& f : *some) got.push_back(f.key + " " + f.entry);
  EXPECT_EQ(got, (std::vector<std::string>{"k1 mean|inside|x", "k1 volume", "k2 volume"}));
  EXPECT_EQ((*some)[0].value, (std::vector<double>{3, 4}));
  auto all = this->features().cached_features({"k1", "k2"}, {});
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->size(), 5u);
}

// A query's results in one transaction: every known surface's entries stored, a surface deleted
// meanwhile skipped without failing the others, a malformed entry refusing the whole batch.
TYPED_TEST(StoreWriteCache, ABatchStoresEverySurfacesEntriesAndSkipsAGoneSurface) {
  auto a = this->store_->add_structure(new_structure("P1", "S1", "a", 1));
  auto b = this->store_->add_structure(new_structure("P1", "S1", "b", 2));
  ASSERT_TRUE(a.ok() && b.ok());
  const std::string gone(64, 'f');
  std::vector<SurfaceFeatures> batch = {{a->structure.surface.sha256, {{"ka", "volume", {1}}}},
                                        {gone, {{"kg", "volume", {9}}}},
                                        {b->structure.surface.sha256, {{"kb", "volume", {2}}, {"kb", "area", {3}}}}};
  ASSERT_TRUE(this->features().put_cached_features(batch).ok());
  auto got = this->features().cached_features({"ka", "kb", "kg"});
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->size(), 3u);  // ka volume, kb volume and area; nothing of the gone surface
  for (const CachedFeature& f : *got) EXPECT_NE(f.key, "kg");

  batch[0].entries[0].entry = "";
  const Status s = this->features().put_cached_features(batch);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(this->features().put_cached_features(std::vector<SurfaceFeatures>{}).ok());
}

}  // namespace
}  // namespace soiq::db
