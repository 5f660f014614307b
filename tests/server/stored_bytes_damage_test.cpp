// Damaged stored bytes seen through the server's engines, on each real engine (SQLite and
// PostgreSQL, tests/db/raw_store.h): a surface blob, an image blob or a cached value changed in
// place with SQL, as a failing disk would, gives DATA_LOSS naming the structure (and the surface,
// series or feature) when a feature is computed or queried, never a value; a query fails only the
// structure whose stored bytes are damaged; an upload of the same mesh repairs its surface.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "db/cached_value.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"
#include "server/app/feature_engine.h"
#include "server/app/query_engine.h"
#include "server/app/stored_structure_features.h"
#include "tests/db/raw_store.h"
#include "tests/db/temp_store.h"
#include "tests/server/stored_box.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::TempDir;

template <typename Raw>
class StoredBytesDamage : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = raw_.open();
    ASSERT_NE(store_, nullptr);
  }

  // A box of `x` x 10 x 10 mm at a place of its own (its own surface): mesh_volume_mm3 = 100 x.
  int64_t add_box(const std::string& name, double x) {
    const double at = double(++boxes_) * 100;
    return testing::add_stored_box(*store_, {at, 0, 0}, {at + x, 10, 10}, name);
  }

  // A fresh engine, as after a restart: nothing decoded is cached in memory.
  std::unique_ptr<FeatureEngine> engine() {
    return std::make_unique<FeatureEngine>(*store_, int64_t(1) << 26, budget_);
  }

  // On a grid of `spacing_mm`: each grid is a cache key of its own.
  static FeatureAsk volume_ask(double spacing_mm = 1) {
    FeatureAsk ask;
    ask.names = {"mesh_volume_mm3"};
    ask.grid.spacing_mm = {spacing_mm, spacing_mm, spacing_mm};
    EXPECT_TRUE(complete_feature_ask(ask).ok());
    return ask;
  }

  Result<FeatureValues> compute(int64_t id, const FeatureAsk& ask) {
    SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord s, store_->get_structure(id));
    SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store_->list_series(s.study_uid));
    std::unique_ptr<FeatureEngine> features = engine();
    SOIQ_ASSIGN_OR_RETURN(const FeaturePlan plan, features->plan(s, series, ask));
    return features->compute(plan, ask);
  }

  Result<QuerySummary> query_volumes(std::vector<QueryRow>& rows, double spacing_mm = 1) {
    Query q;
    q.limit = 100;
    QueryFeature f;
    f.name = "mesh_volume_mm3";
    f.label.name = f.name;
    q.features = {f};
    q.ask = volume_ask(spacing_mm);
    std::unique_ptr<FeatureEngine> features = engine();
    QueryEngine queries(*store_, *features, pool_, QueryLimits{});
    const QueryOutput out{[](const QueryProgress&) { return ok_status(); },
                          [&](QueryRow&& r) {
                            rows.push_back(std::move(r));
                            return ok_status();
                          }};
    return queries.run(
        q, [] { return ok_status(); }, out);
  }

  // Flips bit `bit` of byte `at` (from the end when negative) of a stored blob, in place with SQL.
  void flip_blob(const char* table, const std::string& sha, const std::string& blob, long at, int bit) {
    std::string bytes = blob;
    const size_t i = at >= 0 ? size_t(at) : bytes.size() - size_t(-at);
    bytes[i] = char(bytes[i] ^ (1 << bit));
    raw_.run(std::string("UPDATE ") + table + " SET blob = ?1 WHERE sha256 = ?2", bytes, {sha});
  }

  TempDir dir_;
  Raw raw_{dir_};
  std::unique_ptr<db::SqlStore> store_;
  MemoryBudget budget_{int64_t(1) << 30};
  WorkerPool pool_{2};
  int boxes_ = 0;
};

TYPED_TEST_SUITE(StoredBytesDamage, db::testing::RawBackends, db::testing::StoreBackendNames);

TYPED_TEST(StoredBytesDamage, AFlippedBitInASurfaceBlobIsDataLossNamingTheStructureNeverAValue) {
  const int64_t id = this->add_box("box", 12);
  const Result<FeatureValues> sound = this->compute(id, this->volume_ask());
  ASSERT_TRUE(sound.ok()) << sound.status().to_string();
  ASSERT_NEAR(sound->at("mesh_volume_mm3").at(0), 1200, 1e-9);
  const std::string sha = this->store_->get_structure(id)->surface.sha256;
  const std::string blob = *this->store_->get_surface_blob(sha);

  this->flip_blob("surfaces", sha, blob, long(blob.size() / 2), 3);
  const Result<FeatureValues> damaged = this->compute(id, this->volume_ask());
  ASSERT_FALSE(damaged.ok()) << "a value from a damaged surface: " << damaged->at("mesh_volume_mm3").at(0);
  EXPECT_EQ(damaged.status().code(), StatusCode::kDataLoss);
  const std::string& m = damaged.status().message();
  EXPECT_TRUE(contains(m, "structure " + std::to_string(id) + " (surface sha256 " + sha + ")")) << m;
  EXPECT_TRUE(contains(m, "stored surface is corrupt")) << m;
  EXPECT_TRUE(contains(m, "checksum mismatch")) << m;
  EXPECT_TRUE(contains(m, "restore the store from a backup")) << m;

  // A query on a grid not cached yet reports the structure as failed for that reason, with no row.
  std::vector<QueryRow> rows;
  const Result<QuerySummary> summary = this->query_volumes(rows, 0.5);
  ASSERT_TRUE(summary.ok()) << summary.status().to_string();
  EXPECT_TRUE(rows.empty());
  EXPECT_EQ(summary->failed, 1);
  ASSERT_EQ(summary->failures.size(), 1u);
  EXPECT_TRUE(contains(summary->failures[0], "DATA_LOSS")) << summary->failures[0];
  EXPECT_TRUE(contains(summary->failures[0], "checksum mismatch")) << summary->failures[0];

  // An upload of the same mesh replaces the damaged blob: the structure computes again.
  this->boxes_ = 0;
  ASSERT_GT(this->add_box("box again", 12), 0);
  const Result<FeatureValues> repaired = this->compute(id, this->volume_ask());
  ASSERT_TRUE(repaired.ok()) << repaired.status().to_string();
  EXPECT_EQ(repaired->at("mesh_volume_mm3"), sound->at("mesh_volume_mm3"));
}

// A version 2 blob (stored before checksums) that decodes to another mesh is caught by its
// sha256, which a blob without a checksum is checked against.
TYPED_TEST(StoredBytesDamage, AVersion2BlobThatDecodesToAnotherMeshIsDataLoss) {
  const int64_t id = this->add_box("box", 12);
  const std::string sha = this->store_->get_structure(id)->surface.sha256;
  std::string v2 = "SOIQSRF2" + this->store_->get_surface_blob(sha)->substr(12);
  bool silent = false;
  for (size_t at = 24; at < v2.size() && !silent; ++at) {
    v2[at] = char(v2[at] ^ 0x01);
    Result<TriangleMesh> other = db::decode_surface(v2);
    silent = other.ok() && db::surface_sha256(*other) != sha;
    if (!silent) v2[at] = char(v2[at] ^ 0x01);
  }
  ASSERT_TRUE(silent);
  this->raw_.run("UPDATE surfaces SET blob = ?1 WHERE sha256 = ?2", v2, {sha});
  const Result<FeatureValues> damaged = this->compute(id, this->volume_ask());
  ASSERT_FALSE(damaged.ok());
  EXPECT_EQ(damaged.status().code(), StatusCode::kDataLoss);
  EXPECT_TRUE(contains(damaged.status().message(), "structure " + std::to_string(id))) << damaged.status().message();
  EXPECT_TRUE(contains(damaged.status().message(), "without a checksum) decodes to a mesh of sha256"))
      << damaged.status().message();
}

TYPED_TEST(StoredBytesDamage, AFlippedBitInAnImageBlobIsDataLossNamingTheStructureAndSeries) {
  const int64_t id = this->add_box("box", 1);  // x 100..101, y and z 0..10
  // A PT image of 4s over the box, on a 1 mm grid.
  db::NewSeries s;
  s.patient.patient_id = "P1";
  s.study.study_uid = "S1";
  s.series.series_uid = "1.2.9";
  s.series.modality = "PT";
  Image image;
  image.geometry.dims = {6, 14, 14};
  image.geometry.origin_mm = {98, -2, -2};
  image.voxels.assign(6 * 14 * 14, 4.0f);
  s.series.geometry = image.geometry;
  const Result<db::EncodedImage> encoded = db::encode_image(image);
  ASSERT_TRUE(encoded.ok());
  s.series.sha256 = encoded->sha256;
  s.image_blob = encoded->blob;
  ASSERT_TRUE(this->store_->put_series(s).ok());
  FeatureAsk ask;
  ask.names = {"mean"};
  ask.images = {"PT"};
  ASSERT_TRUE(complete_feature_ask(ask).ok());
  const Result<FeatureValues> sound = this->compute(id, ask);
  ASSERT_TRUE(sound.ok()) << sound.status().to_string();
  ASSERT_EQ(sound->begin()->second, std::vector<double>{4.0});

  this->flip_blob("image_blobs", s.series.sha256, s.image_blob, -1, 0);
  const Result<FeatureValues> damaged = this->compute(id, ask);
  ASSERT_FALSE(damaged.ok());
  EXPECT_EQ(damaged.status().code(), StatusCode::kDataLoss);
  const std::string& m = damaged.status().message();
  EXPECT_TRUE(contains(m, "structure " + std::to_string(id) + ": image of series 1.2.9")) << m;
  EXPECT_TRUE(contains(m, "stored image is corrupt")) << m;
}

// A damaged cached value fails its structure (DATA_LOSS naming it and the feature), in a query and
// when the structure's features are asked; the other structures of the query are answered.
TYPED_TEST(StoredBytesDamage, AFlippedBitInACachedValueFailsOnlyItsStructure) {
  const int64_t a = this->add_box("a", 10);
  const int64_t b = this->add_box("b", 20);
  std::vector<QueryRow> rows;
  ASSERT_TRUE(this->query_volumes(rows).ok());  // computes both, and caches them
  ASSERT_EQ(rows.size(), 2u);
  const std::string a_sha = this->store_->get_structure(a)->surface.sha256;
  bool flipped = false;
  ASSERT_TRUE(this->store_
                  ->scan_stored(db::StoredKind::kCachedValue,
                                [&](const db::StoredItem& item) {
                                  if (item.surface_sha256 != a_sha || item.entry != "mesh_volume_mm3")
                                    return ok_status();
                                  std::string bytes = item.bytes;
                                  bytes[1] = char(bytes[1] ^ 0x40);
                                  this->raw_.run("UPDATE feature_cache SET value = ?1 WHERE key = ?2 AND entry = ?3",
                                                 bytes, {item.key, item.entry});
                                  flipped = true;
                                  return ok_status();
                                })
                  .ok());
  ASSERT_TRUE(flipped);

  rows.clear();
  const Result<QuerySummary> summary = this->query_volumes(rows);
  ASSERT_TRUE(summary.ok()) << summary.status().to_string();
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].structure.id, b);
  EXPECT_EQ(summary->cache_hits, 1);
  EXPECT_EQ(summary->failed, 1);
  ASSERT_EQ(summary->failures.size(), 1u);
  const std::string& failure = summary->failures[0];
  EXPECT_TRUE(contains(failure, "DATA_LOSS")) << failure;
  EXPECT_TRUE(contains(failure, "structure " + std::to_string(a) + ": cached feature 'mesh_volume_mm3'")) << failure;

  std::unique_ptr<FeatureEngine> features = this->engine();
  const Result<StoredStructureFeatures> one =
      stored_structure_features(*this->store_, *features, this->pool_, a, this->volume_ask());
  ASSERT_FALSE(one.ok());
  EXPECT_EQ(one.status().code(), StatusCode::kDataLoss);
  EXPECT_TRUE(contains(one.status().message(), "structure " + std::to_string(a) + ": cached feature 'mesh_volume_mm3'"))
      << one.status().message();
}

}  // namespace
}  // namespace soiq::server
