// Store::import_batch, on every backend: series and structures of one import in one transaction.
#include <gtest/gtest.h>

#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;
using testing::two_series_two_structures;

template <typename Backend>
class StoreImportBatch : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(StoreImportBatch, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreImportBatch, StoresEverySeriesAndStructure) {
  auto r = this->store_->import_batch(two_series_two_structures());
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->series_replaced, (std::vector<bool>{false, false}));
  ASSERT_EQ(r->structures.size(), 2u);
  EXPECT_EQ(r->structures[0].structure.name, "GTV_CT");
  EXPECT_EQ(r->structures[1].structure.study_uid, "S1");
  const Counts n = this->counts();
  EXPECT_EQ(n.patients, 1);
  EXPECT_EQ(n.studies, 1);
  EXPECT_EQ(n.series, 2);
  EXPECT_EQ(n.structures, 2);
  // Stage 1 sees the series' modalities for the structures written after them.
  Stage1Filter f;
  f.modality = "PT";
  auto hits = this->store_->stage1(f, 10);
  ASSERT_TRUE(hits.ok());
  EXPECT_EQ(hits->size(), 2u);
}

TYPED_TEST(StoreImportBatch, InvalidItemIsRefusedBeforeAnyWrite) {
  ImportBatch b = two_series_two_structures();
  b.structures[1].laterality = "X";
  auto r = this->store_->import_batch(b);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(this->counts().series, 0);
  EXPECT_EQ(this->counts().patients, 0);
}

}  // namespace
}  // namespace soiq::db
