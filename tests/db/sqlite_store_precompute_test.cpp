// SqliteStore's precompute queue and stored features (db/store.h): what queues a structure, what
// put_precomputed stores and when it stores nothing, that the values survive every later write of
// the patient, and the migration that queues what a version-4 file held.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>

#include "db/deflate.h"
#include "db/image_blob.h"
#include "db/sqlite/schema_migrations.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_series;
using testing::new_structure;
using testing::open_store;
using testing::TempDir;

std::vector<int64_t> queued_ids(SqliteStore& store) {
  auto q = store.precompute_queue(1000);
  EXPECT_TRUE(q.ok()) << q.status().to_string();
  std::vector<int64_t> ids;
  if (q.ok())
    for (const StructureRecord& s : *q) ids.push_back(s.id);
  return ids;
}

Precomputed values_for(const StructureRecord& s, double volume) {
  Precomputed p;
  p.structure_id = s.id;
  p.surface_sha256 = s.surface.sha256;
  p.definitions_version = 7;
  p.values.assign(stored_feature_names().size(), std::optional<double>(0.5));
  p.values[0] = volume;  // voxel_volume_mm3
  p.cache_entries = {{"v7|" + s.surface.sha256 + "|grid|nonzero|", "voxel_volume_mm3", {volume}}};
  return p;
}

// The ids stage 1 keeps with voxel_volume_mm3 > 100.
std::vector<int64_t> large(SqliteStore& store) {
  Stage1Filter f;
  f.stored_features.push_back({"voxel_volume_mm3", ">", 100});
  auto got = store.stage1(f, 1000);
  EXPECT_TRUE(got.ok()) << got.status().to_string();
  std::vector<int64_t> ids;
  if (got.ok())
    for (const Candidate& c : *got) ids.push_back(c.structure.id);
  return ids;
}

class Precompute : public ::testing::Test {
 protected:
  TempDir dir_;
  std::unique_ptr<SqliteStore> store_ = open_store(dir_.file("p.db"));
};

TEST_F(Precompute, ANewStructureIsQueuedAndLeavesTheQueueWithItsValues) {
  auto a = store_->add_structure(new_structure("P1", "1.1", "A", 0));
  auto b = store_->add_structure(new_structure("P1", "1.1", "B", 3));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(queued_ids(*store_), (std::vector<int64_t>{a->structure.id, b->structure.id}));
  EXPECT_EQ(store_->counts()->precompute_queued, 2);
  // Unstored structures pass a stored-feature condition: stage 2 decides them.
  EXPECT_EQ(large(*store_), (std::vector<int64_t>{a->structure.id, b->structure.id}));

  ASSERT_TRUE(store_->put_precomputed(values_for(a->structure, 50)).ok());
  ASSERT_TRUE(store_->put_precomputed(values_for(b->structure, 500)).ok());
  EXPECT_TRUE(queued_ids(*store_).empty());
  EXPECT_EQ(large(*store_), (std::vector<int64_t>{b->structure.id}));
  auto cached = store_->cached_features({"v7|" + b->structure.surface.sha256 + "|grid|nonzero|"});
  ASSERT_TRUE(cached.ok());
  ASSERT_EQ(cached->size(), 1u);
  EXPECT_EQ(cached->at(0).value, std::vector<double>{500});

  // Another structure and a series of the same patient rewrite its stage-1 rows: the values stay.
  ASSERT_TRUE(store_->add_structure(new_structure("P1", "1.2", "C", 6)).ok());
  const std::vector<int64_t> after = large(*store_);
  ASSERT_EQ(after.size(), 2u);  // b, and C (not stored yet)
  EXPECT_EQ(after[0], b->structure.id);
}

TEST_F(Precompute, AFailureLeavesTheQueueAndIsCountedAndTheStructureStillReachesStage2) {
  auto a = store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  Precomputed failed;
  failed.structure_id = a->structure.id;
  failed.surface_sha256 = a->structure.surface.sha256;
  failed.failure = "RESOURCE_EXHAUSTED: grid too large";
  ASSERT_TRUE(store_->put_precomputed(failed).ok());
  EXPECT_TRUE(queued_ids(*store_).empty());
  EXPECT_EQ(store_->counts()->precompute_failed, 1);
  EXPECT_EQ(large(*store_), std::vector<int64_t>{a->structure.id});
  // A new image in its study queues it again (its failure may have been the image).
  ASSERT_TRUE(store_->put_series(new_series("P1", "1.1", "1.1.9", 1)).ok());
  EXPECT_EQ(queued_ids(*store_), std::vector<int64_t>{a->structure.id});
  EXPECT_EQ(store_->counts()->precompute_failed, 0);
}

TEST_F(Precompute, ValuesOfASurfaceNoLongerStoredAreDropped) {
  NewStructure s = new_structure("P1", "1.1", "A", 0);
  s.source_uid = "1.2.3/1";
  auto a = store_->add_structure(s);
  ASSERT_TRUE(a.ok());
  // Re-imported with another surface while the worker computed the old one.
  NewStructure moved = new_structure("P1", "1.1", "A", 5);
  moved.source_uid = "1.2.3/1";
  auto b = store_->add_structure(moved);
  ASSERT_TRUE(b.ok() && b->replaced);
  ASSERT_TRUE(store_->put_precomputed(values_for(a->structure, 500)).ok());
  EXPECT_EQ(queued_ids(*store_), std::vector<int64_t>{a->structure.id});  // still to do, on the new surface
  ASSERT_TRUE(store_->put_precomputed(values_for(b->structure, 50)).ok());
  EXPECT_TRUE(queued_ids(*store_).empty());
  EXPECT_TRUE(large(*store_).empty());
  // A new surface forgets the values and queues it; the same surface again keeps them.
  moved = new_structure("P1", "1.1", "A", 9);
  moved.source_uid = "1.2.3/1";
  ASSERT_TRUE(store_->add_structure(moved).ok());
  EXPECT_EQ(queued_ids(*store_), std::vector<int64_t>{a->structure.id});
  EXPECT_EQ(large(*store_), std::vector<int64_t>{a->structure.id});  // unstored: passes to stage 2
  // Deleted while computed: nothing stored, no error.
  ASSERT_TRUE(store_->delete_structure(a->structure.id).ok());
  EXPECT_TRUE(store_->put_precomputed(values_for(b->structure, 50)).ok());
  EXPECT_EQ(store_->counts()->precompute_queued, 0);
}

TEST_F(Precompute, ValuesOfAnotherDefinitionVersionAreQueuedAgain) {
  auto a = store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(store_->put_precomputed(values_for(a->structure, 50)).ok());  // version 7
  EXPECT_EQ(*store_->requeue_precompute(7), 0);
  EXPECT_TRUE(queued_ids(*store_).empty());
  EXPECT_TRUE(large(*store_).empty());
  EXPECT_EQ(*store_->requeue_precompute(8), 1);
  EXPECT_EQ(queued_ids(*store_), std::vector<int64_t>{a->structure.id});
  EXPECT_EQ(large(*store_), std::vector<int64_t>{a->structure.id});
}

TEST_F(Precompute, MalformedValuesAndConditionsAreInvalidArgument) {
  auto a = store_->add_structure(new_structure("P1", "1.1", "A", 0));
  ASSERT_TRUE(a.ok());
  Precomputed p = values_for(a->structure, 1);
  p.values.pop_back();
  EXPECT_EQ(store_->put_precomputed(p).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(queued_ids(*store_).size(), 1u);
  for (const StoredFeatureCondition& c :
       std::vector<StoredFeatureCondition>{{"mean", ">", 1},
                                           {"voxel_volume_mm3); DROP TABLE x; --", ">", 1},
                                           {"sphericity", "LIKE", 1},
                                           {"sphericity", ">", std::nan("")}}) {
    Stage1Filter f;
    f.stored_features.push_back(c);
    auto got = store_->stage1(f, 10);
    EXPECT_EQ(got.status().code(), StatusCode::kInvalidArgument) << c.name << " " << c.op;
  }
}

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
  f.stored_features.push_back({"voxel_volume_mm3", ">", 190});
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

}  // namespace
}  // namespace soiq::db
