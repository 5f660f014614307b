// Stage 1's covering range indexes (schema version 6): a range query with the other structured
// filters is answered inside its index, and a file of version 5 gets the indexes when opened.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/sqlite/schema_migrations.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_structure;
using testing::open_store;
using testing::TempDir;

// A range with every other structured filter: the range's index holds those columns too, so the
// conditions are tested inside it and no stage1_rows row is read (a covering index). Results are
// the oracle's (store_stage1_test.cpp's random combinations check them).
TEST(Stage1Indexes, ARangeWithTheOtherStructuredFiltersReadsOnlyItsIndex) {
  TempDir dir;
  auto store = open_store(dir.file("stage1.db"));
  ASSERT_TRUE(store);
  ASSERT_TRUE(store->add_structure(new_structure("P1", "1.2.3", "Hippocampus")).ok());
  std::vector<Stage1Filter> filters(4);
  for (Stage1Filter& f : filters) {
    f.sex = "F";
    f.modality = "MR";
    f.laterality = "L";
  }
  filters[0].min_age_years = 40, filters[0].max_age_years = 60;
  filters[0].study_date_from = "20100101";
  filters[1].study_date_from = "20100101", filters[1].study_date_to = "20151231";
  filters[1].min_age_years = 20;
  filters[2].birth_date_from = "19500101", filters[2].birth_date_to = "19600101";
  filters[3].structure_name_glob = "Hippo*";
  filters[3].max_age_years = 80;
  for (const Stage1Filter& f : filters) {
    auto plan = store->stage1_plan(f, 100000);
    ASSERT_TRUE(plan.ok()) << plan.status().to_string();
    std::string text;
    for (const std::string& line : *plan) text += line + "\n";
    EXPECT_TRUE(contains(text, "SEARCH r USING COVERING INDEX")) << text;
  }
}

// A file of schema version 5 had one-column range indexes; opening it builds the covering ones.
TEST(Stage1Indexes, AVersion5FileGetsTheCoveringRangeIndexes) {
  TempDir dir;
  const std::string path = dir.file("v5.db");
  {
    auto store = open_store(path);
    ASSERT_TRUE(store);
    ASSERT_TRUE(store->add_structure(new_structure("P1", "1.2.3", "Liver")).ok());
  }
  testing::exec_sql(
      path, std::string(testing::kBackToSchemaV6) +
                "DROP INDEX stage1_rows_age; CREATE INDEX stage1_rows_age ON stage1_rows(age_years); "
                "DROP INDEX stage1_rows_study_date; CREATE INDEX stage1_rows_study_date ON stage1_rows(study_date); "
                "DROP INDEX stage1_rows_birth_date; CREATE INDEX stage1_rows_birth_date ON stage1_rows(birth_date); "
                "DROP INDEX stage1_rows_name_lower; CREATE INDEX stage1_rows_name_lower ON stage1_rows(name_lower); "
                "PRAGMA user_version = 5");
  auto store = open_store(path);
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  Stage1Filter f;
  f.sex = "M";
  f.min_age_years = 10, f.max_age_years = 90;
  auto plan = store->stage1_plan(f, 100);
  ASSERT_TRUE(plan.ok());
  std::string text;
  for (const std::string& line : *plan) text += line + "\n";
  EXPECT_TRUE(contains(text, "COVERING INDEX stage1_rows_age")) << text;
  auto got = store->stage1(Stage1Filter{}, 100);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->size(), 1u);
}

}  // namespace
}  // namespace soiq::db
