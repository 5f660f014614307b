// SqliteStore::stage1 as SQLite plans it, on the random store of the stage-1 tests
// (stage1_random_store.h; its results are checked on every backend in store_stage1_test.cpp).
#include <gtest/gtest.h>

#include <string>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/stage1_random_store.h"
#include "tests/db/store_backends.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::single_filters;

class Stage1 : public testing::Stage1Store<testing::SqliteBackend> {
 protected:
  SqliteStore& sqlite_store() { return dynamic_cast<SqliteStore&>(*store_); }
};

// Every filter on its own, as SQLite plans it: the selective ones are index searches (SEARCH ... USING
// INDEX), so stage 1 never reads every row for them. Not searched, on purpose: sex, laterality and
// modality keep a third of the rows or more and have no index (sqlite_store_stage1.cpp); a glob
// that starts with a wildcard has no prefix to search; a one-sided age or date range keeps a share
// SQLite cannot know without statistics, and it rightly reads the narrow table in id order rather
// than search and sort; `!=` is no range. A stored-feature condition is searched even one-sided:
// selecting few structures out of all is what it is for.
TEST_F(Stage1, EverySelectiveFilterIsAnIndexSearch) {
  for (const auto& [label, set] : single_filters()) {
    Stage1Filter f;
    set(f);
    const bool one_sided = (f.min_age_years.has_value() != f.max_age_years.has_value()) ||
                           (!f.birth_date_from.empty() && f.birth_date_to.empty()) ||
                           (!f.study_date_from.empty() && f.study_date_to.empty());
    const bool not_equal = !f.stored_features.empty() && f.stored_features[0].op == Comparison::kNotEqual;
    const bool unindexed =
        one_sided || not_equal || !f.sex.empty() || !f.laterality.empty() || !f.modality.empty() ||
        (!f.patient_id_glob.empty() && std::string("*?[").find(f.patient_id_glob[0]) != std::string::npos) ||
        (!f.study_description_glob.empty() &&
         std::string("*?[").find(f.study_description_glob[0]) != std::string::npos) ||
        (!f.structure_name_glob.empty() && std::string("*?[").find(f.structure_name_glob[0]) != std::string::npos);
    if (unindexed) continue;
    auto plan = sqlite_store().stage1_plan(f, 100000);
    ASSERT_TRUE(plan.ok()) << label << ": " << plan.status().to_string();
    std::string text;
    for (const std::string& line : *plan) text += line + "\n";
    EXPECT_TRUE(contains(text, "SEARCH r USING INDEX") || contains(text, "SEARCH r USING COVERING INDEX") ||
                contains(text, "SEARCH r USING INTEGER PRIMARY KEY"))
        << label << ":\n"
        << text;
    EXPECT_FALSE(contains(text, "SCAN r")) << label << ":\n" << text;
    EXPECT_FALSE(contains(text, "SCAN stage1_rows")) << label << ":\n" << text;
    if (!f.stored_features.empty()) {
      // The unstored rows by their partial index, then the feature's own index.
      EXPECT_TRUE(contains(text, "stage1_rows_features_unstored")) << label << ":\n" << text;
      EXPECT_TRUE(contains(text, "stage1_rows_" + f.stored_features[0].name)) << label << ":\n" << text;
    }
  }
}

}  // namespace
}  // namespace soiq::db
