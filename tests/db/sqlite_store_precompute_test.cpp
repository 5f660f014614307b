// SqliteStore's precompute in the SQLite file: a stored-feature condition stays an index search
// whatever SQLite's statistics say, and the migration that queues what a version-4 file held (the
// queue and stored values themselves are tested on every backend in store_precompute_test.cpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <memory>
#include <string>
#include <vector>

#include "db/deflate.h"
#include "db/image_blob.h"
#include "db/sqlite/schema_migrations.h"
#include "tests/db/precompute_values.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::large;
using testing::new_series;
using testing::new_structure;
using testing::open_store;
using testing::queued_ids;
using testing::TempDir;
using testing::values_for;

class Precompute : public ::testing::Test {
 protected:
  TempDir dir_;
  std::unique_ptr<SqliteStore> store_ = open_store(dir_.file("p.db"));
};

// SQLite's statistics (PRAGMA optimize when soiqd stops) may be taken while nothing is stored: the
// partial index of unstored rows then holds every row. Once values are stored, a content filter must
// still be two index searches, not a scan of every row.
TEST_F(Precompute, AContentFilterIsSearchedByIndexWhateverTheStatisticsSay) {
  std::vector<StructureRecord> all;
  for (int i = 0; i < 200; ++i) {
    auto a = store_->add_structure(new_structure("P" + std::to_string(i), "1." + std::to_string(i), "A", i % 40));
    ASSERT_TRUE(a.ok());
    all.push_back(a->structure);
  }
  testing::exec_sql(dir_.file("p.db"), "ANALYZE");
  store_.reset();
  store_ = open_store(dir_.file("p.db"));
  for (const StructureRecord& s : all) ASSERT_TRUE(store_->put_precomputed(values_for(s, double(s.id))).ok());
  Stage1Filter f;
  f.stored_features.push_back({"voxel_volume_mm3", Comparison::kGreater, 190});
  auto plan = store_->stage1_plan(f, 1000);
  ASSERT_TRUE(plan.ok()) << plan.status().to_string();
  std::string text;
  for (const std::string& line : *plan) text += line + "\n";
  EXPECT_EQ(text.find("SCAN"), std::string::npos) << text;
  EXPECT_NE(text.find("stage1_rows_voxel_volume_mm3"), std::string::npos) << text;
  EXPECT_EQ(large(*store_).size(), 100u);  // ids 101..200: large() asks voxel_volume_mm3 > 100
}

TEST(SchemaMigration5, EveryStructureOfAVersion4FileIsQueuedAndEveryImageReencoded) {
  TempDir dir;
  const std::string path = dir.file("v4.db");
  const NewSeries series = new_series("P1", "1.1", "1.1.7", 42.5f);
  {
    auto store = open_store(path);
    ASSERT_TRUE(store->add_structure(new_structure("P1", "1.1", "A", 0)).ok());
    ASSERT_TRUE(store->add_structure(new_structure("P2", "2.1", "B", 2)).ok());
    ASSERT_TRUE(store->put_series(series).ok());
  }
  // The image as a version-4 soiqd stored it: its raw voxels deflated.
  auto decoded = decode_image(series.image_blob, series.series.geometry);
  ASSERT_TRUE(decoded.ok());
  auto v1 = deflate_bytes(decoded->voxels.data(), decoded->voxels.size() * sizeof(float));
  ASSERT_TRUE(v1.ok());
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, "UPDATE image_blobs SET blob = ?", -1, &st, nullptr), SQLITE_OK);
    sqlite3_bind_blob(st, 1, v1->data(), int(v1->size()), SQLITE_TRANSIENT);
    ASSERT_EQ(sqlite3_step(st), SQLITE_DONE);
    sqlite3_finalize(st);
    sqlite3_close(db);
  }
  testing::exec_sql(path, std::string(testing::kBackToSchemaV4) + "PRAGMA user_version = 4");
  auto store = open_store(path);
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  EXPECT_EQ(queued_ids(*store).size(), 2u);
  EXPECT_EQ(large(*store).size(), 2u);
  auto blob = store->get_image_blob("1.1.7");
  ASSERT_TRUE(blob.ok());
  EXPECT_FALSE(is_deflated_image_blob(*blob));
  EXPECT_EQ(*blob, series.image_blob);  // what this version writes, bit for bit
}

TEST(SqlitePrecomputeMigration, AFileOfSchemaTwelveKeepsItsValuesAsTheDefaultSet) {
  TempDir dir;
  const std::string path = dir.file("v12.db");
  int64_t id = 0;
  {
    auto store = open_store(path);
    auto a = store->add_structure(new_structure("P1", "1.1", "A", 0));
    ASSERT_TRUE(a.ok());
    id = a->structure.id;
    ASSERT_TRUE(store->put_precomputed(values_for(a->structure, 500)).ok());
  }
  testing::exec_sql(path, std::string(testing::kBackToSchemaV12) + "PRAGMA user_version = 12");
  auto store = open_store(path);
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  EXPECT_EQ(large(*store), std::vector<int64_t>{id});
  EXPECT_EQ(*store->requeue_precompute(7, PrecomputedSet::kDefault), 0);
  EXPECT_EQ(*store->requeue_precompute(7, PrecomputedSet::kWithWeighted), 1);
  EXPECT_EQ(queued_ids(*store), std::vector<int64_t>{id});
}

}  // namespace
}  // namespace soiq::db
