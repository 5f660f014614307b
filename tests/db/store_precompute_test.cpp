// The Store's precompute queue and stored features (db/store.h), on every backend: what queues a
// structure, what put_precomputed stores and when it stores nothing, and that the values survive
// every later write of the patient.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/precompute_values.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::large;
using testing::new_series;
using testing::new_structure;
using testing::queued_ids;
using testing::values_for;

template <typename Backend>
class Precompute : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(Precompute, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(Precompute, ANewStructureIsQueuedAndLeavesTheQueueWithItsValues) {
  auto a = this->store_->add_structure(new_structure("P1", "1.1", "A", 0));
  auto b = this->store_->add_structure(new_structure("P1", "1.1", "B", 3));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(queued_ids(*this->store_), (std::vector<int64_t>{a->structure.id, b->structure.id}));
  EXPECT_EQ(this->store_->counts()->precompute_queued, 2);
  // Unstored structures pass a stored-feature condition: stage 2 decides them.
  EXPECT_EQ(large(*this->store_), (std::vector<int64_t>{a->structure.id, b->structure.id}));

  ASSERT_TRUE(this->features().put_precomputed(values_for(a->structure, 50)).ok());
  ASSERT_TRUE(this->features().put_precomputed(values_for(b->structure, 500)).ok());
  EXPECT_TRUE(queued_ids(*this->store_).empty());
  EXPECT_EQ(large(*this->store_), (std::vector<int64_t>{b->structure.id}));
  auto cached = this->features().cached_features({"v7|" + b->structure.surface.sha256 + "|grid|nonzero|"});
  ASSERT_TRUE(cached.ok());
  ASSERT_EQ(cached->size(), 1u);
  EXPECT_EQ(cached->at(0).value, std::vector<double>{500});

  // Another structure and a series of the same patient rewrite its stage-1 rows: the values stay.
  ASSERT_TRUE(this->store_->add_structure(new_structure("P1", "1.2", "C", 6)).ok());
  const std::vector<int64_t> after = large(*this->store_);
  ASSERT_EQ(after.size(), 2u);  // b, and C (not stored yet)
  EXPECT_EQ(after[0], b->structure.id);
}

TYPED_TEST(Precompute, AFailureLeavesTheQueueAndIsCountedAndTheStructureStillReachesStage2) {
  auto a = this->store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  Precomputed failed;
  failed.structure_id = a->structure.id;
  failed.surface_sha256 = a->structure.surface.sha256;
  failed.failure = "RESOURCE_EXHAUSTED: grid too large";
  ASSERT_TRUE(this->features().put_precomputed(failed).ok());
  EXPECT_TRUE(queued_ids(*this->store_).empty());
  EXPECT_EQ(this->store_->counts()->precompute_failed, 1);
  EXPECT_EQ(large(*this->store_), std::vector<int64_t>{a->structure.id});
  // A new image in its study queues it again (its failure may have been the image).
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "1.1", "1.1.9", 1)).ok());
  EXPECT_EQ(queued_ids(*this->store_), std::vector<int64_t>{a->structure.id});
  EXPECT_EQ(this->store_->counts()->precompute_failed, 0);
}

TYPED_TEST(Precompute, ValuesOfASurfaceNoLongerStoredAreDropped) {
  NewStructure s = new_structure("P1", "1.1", "A", 0);
  s.source_uid = "1.2.3/1";
  auto a = this->store_->add_structure(s);
  ASSERT_TRUE(a.ok());
  // Re-imported with another surface while the worker computed the old one.
  NewStructure moved = new_structure("P1", "1.1", "A", 5);
  moved.source_uid = "1.2.3/1";
  auto b = this->store_->add_structure(moved);
  ASSERT_TRUE(b.ok() && b->replaced);
  ASSERT_TRUE(this->features().put_precomputed(values_for(a->structure, 500)).ok());
  EXPECT_EQ(queued_ids(*this->store_), std::vector<int64_t>{a->structure.id});  // still to do, on the new surface
  ASSERT_TRUE(this->features().put_precomputed(values_for(b->structure, 50)).ok());
  EXPECT_TRUE(queued_ids(*this->store_).empty());
  EXPECT_TRUE(large(*this->store_).empty());
  // A new surface forgets the values and queues it; the same surface again keeps them.
  moved = new_structure("P1", "1.1", "A", 9);
  moved.source_uid = "1.2.3/1";
  ASSERT_TRUE(this->store_->add_structure(moved).ok());
  EXPECT_EQ(queued_ids(*this->store_), std::vector<int64_t>{a->structure.id});
  EXPECT_EQ(large(*this->store_), std::vector<int64_t>{a->structure.id});  // unstored: passes to stage 2
  // Deleted while computed: nothing stored, no error.
  ASSERT_TRUE(this->store_->delete_structure(a->structure.id).ok());
  EXPECT_TRUE(this->features().put_precomputed(values_for(b->structure, 50)).ok());
  EXPECT_EQ(this->store_->counts()->precompute_queued, 0);
}

TYPED_TEST(Precompute, ValuesOfAnotherDefinitionVersionAreQueuedAgain) {
  auto a = this->store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(this->features().put_precomputed(values_for(a->structure, 50)).ok());  // version 7
  EXPECT_EQ(*this->features().requeue_precompute(7, PrecomputedSet::kDefault), 0);
  EXPECT_TRUE(queued_ids(*this->store_).empty());
  EXPECT_TRUE(large(*this->store_).empty());
  EXPECT_EQ(*this->features().requeue_precompute(8, PrecomputedSet::kDefault), 1);
  EXPECT_EQ(queued_ids(*this->store_), std::vector<int64_t>{a->structure.id});
  EXPECT_EQ(large(*this->store_), std::vector<int64_t>{a->structure.id});
}

TYPED_TEST(Precompute, ALargerSetQueuesAgainAndKeepsTheValuesStage1Reads) {
  auto a = this->store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(this->features().put_precomputed(values_for(a->structure, 500)).ok());  // the default set
  EXPECT_EQ(*this->features().requeue_precompute(7, PrecomputedSet::kWithWeighted), 1);
  EXPECT_EQ(queued_ids(*this->store_), std::vector<int64_t>{a->structure.id});
  // Still stored: a stored-feature condition goes on deciding it in stage 1.
  Stage1Filter small;
  small.stored_features.push_back({"voxel_volume_mm3", Comparison::kLess, 100});
  EXPECT_TRUE(this->store_->stage1(small, 10)->empty());
  EXPECT_EQ(large(*this->store_), std::vector<int64_t>{a->structure.id});

  Precomputed wider = values_for(a->structure, 500);
  wider.set = PrecomputedSet::kWithWeighted;
  ASSERT_TRUE(this->features().put_precomputed(wider).ok());
  EXPECT_TRUE(queued_ids(*this->store_).empty());
  EXPECT_EQ(*this->features().requeue_precompute(7, PrecomputedSet::kWithWeighted), 0);
  // The smaller set again (the option turned off) keeps the values and queues nothing.
  EXPECT_EQ(*this->features().requeue_precompute(7, PrecomputedSet::kDefault), 0);
  EXPECT_TRUE(queued_ids(*this->store_).empty());
  EXPECT_EQ(large(*this->store_), std::vector<int64_t>{a->structure.id});
}

TYPED_TEST(Precompute, MalformedValuesAndConditionsAreInvalidArgument) {
  auto a = this->store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  Precomputed p = values_for(a->structure, 1);
  p.values.pop_back();
  EXPECT_EQ(this->features().put_precomputed(p).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(queued_ids(*this->store_).size(), 1u);
  for (const StoredFeatureCondition& c :
       std::vector<StoredFeatureCondition>{{"mean", Comparison::kGreater, 1},
                                           {"voxel_volume_mm3); DROP TABLE x; --", Comparison::kGreater, 1},
                                           {"sphericity", static_cast<Comparison>(17), 1},
                                           {"sphericity", Comparison::kGreater, std::nan("")}}) {
    Stage1Filter f;
    f.stored_features.push_back(c);
    auto got = this->store_->stage1(f, 10);
    EXPECT_EQ(got.status().code(), StatusCode::kInvalidArgument) << c.name << " " << comparison_symbol(c.op);
  }
}

}  // namespace
}  // namespace soiq::db
