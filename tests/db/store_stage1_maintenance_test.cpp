// Store::stage1 after later writes, on every backend: changed and deleted patients, studies and
// series are seen by the next stage 1 (its indexes and joins follow every write).
#include <gtest/gtest.h>

#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_structure;

std::vector<int64_t> stage1_ids(Store& store, const Stage1Filter& f) {
  auto got = store.stage1(f, 1000);
  EXPECT_TRUE(got.ok()) << got.status().to_string();
  std::vector<int64_t> ids;
  if (got.ok()) {
    for (const Candidate& c : *got) ids.push_back(c.structure.id);
  }
  return ids;
}

template <typename Backend>
class Stage1Maintenance : public testing::StoreTest<Backend> {};
TYPED_TEST_SUITE(Stage1Maintenance, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(Stage1Maintenance, LaterPatientStudyAndSeriesChangesAndDeletesAreSeen) {
  Store* store = this->store_.get();
  const int64_t a = store->add_structure(new_structure("P1", "S1", "Hippocampus"))->structure.id;
  const int64_t b = store->add_structure(new_structure("P1", "S2", "Amygdala"))->structure.id;
  Stage1Filter female;
  female.sex = "F";
  EXPECT_TRUE(stage1_ids(*store, female).empty());
  NewStructure update = new_structure("P1", "S3", "Insula");
  update.patient.sex = "F";
  update.patient.birth_date = "19500101";
  const int64_t c = store->add_structure(update)->structure.id;
  EXPECT_EQ(stage1_ids(*store, female), (std::vector<int64_t>{a, b, c}));

  NewStructure dated = new_structure("P1", "S1", "Thalamus");
  dated.study.study_date = "20100101";  // S1's date, so S1's computed age, changes
  const int64_t d = store->add_structure(dated)->structure.id;
  Stage1Filter sixty;
  sixty.min_age_years = 60.0;
  EXPECT_EQ(stage1_ids(*store, sixty), (std::vector<int64_t>{a, d}));

  Stage1Filter pet;
  pet.modality = "PT";
  EXPECT_TRUE(stage1_ids(*store, pet).empty());
  NewSeries series = testing::new_series("P1", "S2", "SE1", 1.0f);
  series.series.modality = "PT";
  ASSERT_TRUE(store->put_series(series).ok());
  EXPECT_EQ(stage1_ids(*store, pet), (std::vector<int64_t>{b}));
  series.series.modality = "CT";  // replaced: no longer PT
  ASSERT_TRUE(store->put_series(series).ok());
  EXPECT_TRUE(stage1_ids(*store, pet).empty());

  ASSERT_TRUE(store->delete_structure(a).ok());
  EXPECT_EQ(stage1_ids(*store, female), (std::vector<int64_t>{b, c, d}));
  ASSERT_TRUE(store->delete_patient("P1").ok());
  EXPECT_TRUE(stage1_ids(*store, Stage1Filter{}).empty());
}

}  // namespace
}  // namespace soiq::db
