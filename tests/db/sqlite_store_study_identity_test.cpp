// Schema version 3 of the SQLite file: a version-2 file, without a study's Study Time, Study ID and
// Accession Number, is migrated keeping its studies (the values themselves are tested on every
// backend in store_study_identity_test.cpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "db/sqlite/schema_migrations.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::open_store;
using testing::series_of_identified_study;
using testing::TempDir;

TEST(SqliteStoreStudyIdentity, VersionTwoFileIsMigratedKeepingItsStudies) {
  TempDir dir;
  const std::string path = dir.file("v2.db");
  {
    auto store = open_store(path);
    ASSERT_TRUE(store->put_series(new_series("P1", "1.2.3", "1.2.3.4", 1.0f)).ok());
  }
  // Exactly what a version-2 soiqd wrote.
  testing::exec_sql(path, std::string(testing::kBackToSchemaV3) +
                              "ALTER TABLE studies DROP COLUMN accession_number; ALTER TABLE studies DROP COLUMN "
                              "study_id; ALTER TABLE studies DROP COLUMN study_time; PRAGMA user_version = 2;");
  auto store = open_store(path);
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  auto old = store->get_study("1.2.3");
  ASSERT_TRUE(old.ok()) << old.status().to_string();
  EXPECT_EQ(old->accession_number, "");  // unknown for studies stored before
  ASSERT_TRUE(store->put_series(series_of_identified_study()).ok());
  EXPECT_EQ(store->get_study("1.2.3")->accession_number, "ACC0042");
}

}  // namespace
}  // namespace soiq::db
