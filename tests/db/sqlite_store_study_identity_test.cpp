// Schema version 3: a study's DICOM Study Time, Study ID and Accession Number (for the SEGs soiq
// exports on it), kept across updates that do not give them, and the migration of a version-2 file.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "db/sqlite/schema_migrations.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;
using testing::open_store;
using testing::TempDir;

NewSeries series_of_identified_study() {
  NewSeries s = new_series("P1", "1.2.3", "1.2.3.4", 1.0f);
  s.study.study_time = "101512.5";
  s.study.study_id = "S-17";
  s.study.accession_number = "ACC0042";
  return s;
}

TEST(SqliteStoreStudyIdentity, StudyTimeIdAndAccessionNumberRoundTrip) {
  TempDir dir;
  auto store = open_store(dir.file("s.db"));
  ASSERT_TRUE(store->put_series(series_of_identified_study()).ok());
  auto study = store->get_study("1.2.3");
  ASSERT_TRUE(study.ok()) << study.status().to_string();
  EXPECT_EQ(study->study_time, "101512.5");
  EXPECT_EQ(study->study_id, "S-17");
  EXPECT_EQ(study->accession_number, "ACC0042");
  auto listed = store->list_studies("P1", {});
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->items.size(), 1u);
  EXPECT_EQ(listed->items[0].accession_number, "ACC0042");
}

TEST(SqliteStoreStudyIdentity, AWriteWithoutThemKeepsTheStoredValues) {
  TempDir dir;
  auto store = open_store(dir.file("s.db"));
  ASSERT_TRUE(store->put_series(series_of_identified_study()).ok());
  // An upload into the same study knows nothing of its DICOM identity.
  ASSERT_TRUE(store->add_structure(new_structure("P1", "1.2.3", "GTV", 0)).ok());
  auto study = store->get_study("1.2.3");
  ASSERT_TRUE(study.ok());
  EXPECT_EQ(study->study_time, "101512.5");
  EXPECT_EQ(study->study_id, "S-17");
  EXPECT_EQ(study->accession_number, "ACC0042");
}

TEST(SqliteStoreStudyIdentity, AccessionNumberWithAControlCharacterIsRefusedNamingTheField) {
  TempDir dir;
  auto store = open_store(dir.file("s.db"));
  NewSeries s = series_of_identified_study();
  s.study.accession_number = "ACC\n42";
  auto r = store->put_series(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("accession number"), std::string::npos) << r.status().message();
  EXPECT_EQ(store->counts()->studies, 0);
}

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
