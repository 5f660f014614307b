// Store deletes, on every backend: structures and patients, the blobs and cached features they
// leave orphaned, and unknown ids.
#include <gtest/gtest.h>

#include <string>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_series;
using testing::new_structure;

template <typename Backend>
class StoreWriteDelete : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreWriteDelete, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreWriteDelete, DeleteStructureKeepsASharedSurfaceAndDropsAnOrphan) {
  auto a = this->store_->add_structure(new_structure("P1", "S1", "a", 0));
  auto b = this->store_->add_structure(new_structure("P1", "S1", "b", 0));  // same surface as a
  auto c = this->store_->add_structure(new_structure("P1", "S1", "c", 1));
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  const std::string shared = a->structure.surface.sha256, own = c->structure.surface.sha256;
  ASSERT_TRUE(this->store_->put_cached_features(shared, {{"k1", "volume", {1}}}).ok());
  ASSERT_TRUE(this->store_->put_cached_features(own, {{"k2", "volume", {2}}, {"k2", "area", {3}}}).ok());

  EXPECT_EQ(*this->store_->delete_structure(a->structure.id), 1);
  EXPECT_TRUE(this->store_->get_surface_blob(shared).ok());  // b still uses it
  EXPECT_EQ(this->store_->cached_features({"k1"})->size(), 1u);

  EXPECT_EQ(*this->store_->delete_structure(c->structure.id), 1);
  EXPECT_EQ(this->store_->get_surface_blob(own).status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(this->store_->cached_features({"k2"})->empty());
  EXPECT_EQ(this->counts().surfaces, 1);
  EXPECT_EQ(this->counts().cached_features, 1);
}

TYPED_TEST(StoreWriteDelete, DeletePatientCascadesAndRemovesOnlyOrphanBlobs) {
  ASSERT_TRUE(this->store_->add_structure(new_structure("P1", "S1", "a", 0)).ok());
  ASSERT_TRUE(this->store_->add_structure(new_structure("P1", "S1b", "b", 1)).ok());
  auto kept = this->store_->add_structure(new_structure("P2", "S2", "c", 0));  // shares surface 0
  ASSERT_TRUE(kept.ok());
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "S1", "SE1", 1.0f)).ok());
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "S1", "SE1b", 5.0f)).ok());
  ASSERT_TRUE(this->store_->put_series(new_series("P2", "S2", "SE2", 1.0f)).ok());  // shares SE1's image
  const std::string own_surface = encode_surface(testing::tetrahedron(1))->info.sha256;
  ASSERT_TRUE(this->store_->put_cached_features(own_surface, {{"own", "volume", {1}}}).ok());
  ASSERT_TRUE(this->store_->put_cached_features(kept->structure.surface.sha256, {{"shared", "volume", {1}}}).ok());

  auto deleted = this->store_->delete_patient("P1");
  ASSERT_TRUE(deleted.ok()) << deleted.status().to_string();
  EXPECT_EQ(*deleted, 2);
  const Counts n = this->counts();
  EXPECT_EQ(n.patients, 1);
  EXPECT_EQ(n.studies, 1);
  EXPECT_EQ(n.series, 1);
  EXPECT_EQ(n.structures, 1);
  EXPECT_EQ(n.surfaces, 1);
  EXPECT_EQ(n.cached_features, 1);
  EXPECT_TRUE(this->store_->get_image_blob("SE2").ok());  // the shared image blob stayed
  EXPECT_TRUE(this->store_->get_surface_blob(kept->structure.surface.sha256).ok());
  EXPECT_EQ(this->store_->get_study("S1").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(this->store_->get_series("SE1b").status().code(), StatusCode::kNotFound);
}

TYPED_TEST(StoreWriteDelete, UnknownIdsAreNotFoundNamingTheId) {
  const auto expect = [](const Status& s, const std::string& id) {
    EXPECT_EQ(s.code(), StatusCode::kNotFound) << s.to_string();
    EXPECT_TRUE(contains(s.message(), id)) << s.message();
  };
  expect(this->store_->delete_structure(424242).status(), "424242");
  expect(this->store_->get_structure(424243).status(), "424243");
  expect(this->store_->delete_patient("PX1").status(), "PX1");
  expect(this->store_->get_patient("PX2").status(), "PX2");
  expect(this->store_->get_study("1.2.9").status(), "1.2.9");
  expect(this->store_->list_studies("PX3", {}).status(), "PX3");
  expect(this->store_->list_series("1.2.8").status(), "1.2.8");
  expect(this->store_->get_series("SEX").status(), "SEX");
  expect(this->store_->get_image_blob("SEY").status(), "SEY");
  const std::string sha(64, 'a');
  expect(this->store_->get_surface_blob(sha).status(), sha);
  expect(this->store_->put_cached_features(sha, {{"k", "e", {1}}}), sha);
}

}  // namespace
}  // namespace soiq::db
