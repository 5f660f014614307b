// Schema version 2 of the SQLite file: a version-1 file, without the DICOM references of series and
// the source of imported structures, is migrated keeping its data (the references themselves are
// tested on every backend in store_dicom_refs_test.cpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "db/sqlite/schema_migrations.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::imported_structure;
using testing::new_series;
using testing::new_structure;
using testing::open_store;
using testing::TempDir;

TEST(SqliteStoreDicomRefs, VersionOneFileIsMigratedKeepingItsData) {
  TempDir dir;
  const std::string path = dir.file("v1.db");
  int64_t id = 0;
  {
    auto store = open_store(path);
    ASSERT_TRUE(store->put_series(new_series("P1", "1.2.3", "1.2.3.4", 1.0f)).ok());
    auto added = store->add_structure(new_structure("P1", "1.2.3", "GTV", 0));
    ASSERT_TRUE(added.ok());
    id = added->structure.id;
  }
  // Turn the file back into version 1: exactly what a version-1 soiqd wrote.
  testing::exec_sql(
      path,
      (std::string(testing::kBackToSchemaV3) +
       "DROP INDEX structures_source_uid; ALTER TABLE structures DROP COLUMN source_uid; ALTER TABLE structures "
       "DROP COLUMN source_series_uid; ALTER TABLE series DROP COLUMN slice_instance_uids; ALTER TABLE series DROP "
       "COLUMN sop_class_uid; ALTER TABLE series DROP COLUMN frame_of_reference_uid; ALTER TABLE studies DROP "
       "COLUMN accession_number; ALTER TABLE studies DROP COLUMN study_id; ALTER TABLE studies DROP COLUMN "
       "study_time; PRAGMA user_version = 1;")
          .c_str());
  auto store = open_store(path);
  ASSERT_NE(store, nullptr);
  auto got = store->get_structure(id);
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  EXPECT_EQ(got->name, "GTV");
  EXPECT_EQ(got->source_uid, "");
  auto series = store->get_series("1.2.3.4");
  ASSERT_TRUE(series.ok());
  EXPECT_TRUE(series->slice_instance_uids.empty());
  // The new columns work after the migration.
  auto added = store->add_structure(imported_structure("GTV2", 3));
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  EXPECT_EQ(added->structure.source_uid, "1.2.3.77/1");
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
}

}  // namespace
}  // namespace soiq::db
