// SqliteStore::import_batch: series and structures of one import in one transaction.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_series;
using testing::new_structure;
using testing::open_store;
using testing::TempDir;

class SqliteStoreImportBatch : public ::testing::Test {
 protected:
  void SetUp() override { store_ = open_store(dir_.file("store.db")); }
  Counts counts() { return *store_->counts(); }

  TempDir dir_;
  std::unique_ptr<SqliteStore> store_;
};

ImportBatch two_series_two_structures() {
  ImportBatch b;
  b.series.push_back(new_series("P1", "S1", "SE-CT", 1.0f));
  b.series.push_back(new_series("P1", "S1", "SE-PT", 2.0f));
  b.series[1].series.modality = "PT";
  b.structures.push_back(new_structure("P1", "S1", "GTV_CT", 1.0));
  b.structures.push_back(new_structure("P1", "S1", "GTV_PT", 2.0));
  return b;
}

TEST_F(SqliteStoreImportBatch, StoresEverySeriesAndStructure) {
  auto r = store_->import_batch(two_series_two_structures());
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->series_replaced, (std::vector<bool>{false, false}));
  ASSERT_EQ(r->structures.size(), 2u);
  EXPECT_EQ(r->structures[0].structure.name, "GTV_CT");
  EXPECT_EQ(r->structures[1].structure.study_uid, "S1");
  const Counts n = counts();
  EXPECT_EQ(n.patients, 1);
  EXPECT_EQ(n.studies, 1);
  EXPECT_EQ(n.series, 2);
  EXPECT_EQ(n.structures, 2);
  // Stage 1 sees the series' modalities for the structures written after them.
  Stage1Filter f;
  f.modality = "PT";
  auto hits = store_->stage1(f, 10);
  ASSERT_TRUE(hits.ok());
  EXPECT_EQ(hits->size(), 2u);
}

TEST_F(SqliteStoreImportBatch, InvalidItemIsRefusedBeforeAnyWrite) {
  ImportBatch b = two_series_two_structures();
  b.structures[1].laterality = "X";
  auto r = store_->import_batch(b);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(counts().series, 0);
  EXPECT_EQ(counts().patients, 0);
}

TEST_F(SqliteStoreImportBatch, FailureOnTheLastStructureLeavesNothing) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir_.file("store.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TRIGGER fail BEFORE INSERT ON structures WHEN NEW.name = 'GTV_PT' "
                         "BEGIN SELECT RAISE(ABORT, 'injected failure'); END",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  auto r = store_->import_batch(two_series_two_structures());
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.status().message(), "injected failure")) << r.status().message();
  const Counts n = counts();
  EXPECT_EQ(n.patients, 0);
  EXPECT_EQ(n.studies, 0);
  EXPECT_EQ(n.series, 0);
  EXPECT_EQ(n.structures, 0);
  EXPECT_EQ(n.surfaces, 0);
}

}  // namespace
}  // namespace soiq::db
