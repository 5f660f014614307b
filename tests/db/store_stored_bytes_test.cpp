// Stored bytes that soiq did not write as they are, on each real engine (raw_store.h): a blob or
// cached value changed in place with SQL (a failing disk) is refused when read, never read as
// other numbers; an upload or import of the same mesh or image repairs a damaged blob; a store of
// the schema before checksums gets them when opened, a damaged blob left for soiqd to refuse; a
// store opened read only is left as it is.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <string>

#include "db/cached_value.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"
#include "tests/db/raw_store.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_series;
using testing::new_structure;
using testing::TempDir;

template <typename Raw>
class StoreStoredBytes : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = raw_.open();
    ASSERT_NE(store_, nullptr);
  }

  // Every stored item of `kind` by key ("key|entry" for cached values), as scan_stored reads it.
  std::map<std::string, StoredItem> stored(StoredKind kind) {
    std::map<std::string, StoredItem> out;
    const Status s = store_->scan_stored(kind, [&](const StoredItem& item) {
      const std::string key = kind == StoredKind::kCachedValue ? item.key + "|" + item.entry : item.key;
      EXPECT_EQ(out.count(key), 0u) << key << " visited twice";
      out[key] = item;
      return ok_status();
    });
    EXPECT_TRUE(s.ok()) << s.to_string();
    return out;
  }

  void write_surface_blob(const std::string& sha, const std::string& blob) {
    raw_.run("UPDATE surfaces SET blob = ?1 WHERE sha256 = ?2", blob, {sha});
  }
  void write_value(const std::string& key, const std::string& entry, const std::string& bytes) {
    raw_.run("UPDATE feature_cache SET value = ?1 WHERE key = ?2 AND entry = ?3", bytes, {key, entry});
  }

  TempDir dir_;
  Raw raw_{dir_};
  std::unique_ptr<SqlStore> store_;
};

TYPED_TEST_SUITE(StoreStoredBytes, testing::RawBackends, testing::StoreBackendNames);

TYPED_TEST(StoreStoredBytes, ACachedValueFlippedInPlaceIsDataLossNamingItsKeyAndEntry) {
  auto added = this->store_->add_structure(new_structure("P1", "1.1", "s", 1));
  ASSERT_TRUE(added.ok());
  const std::string sha = added->structure.surface.sha256;
  ASSERT_TRUE(this->store_->put_cached_features(sha, {{"k1", "volume", {3313.8}}, {"k1", "area", {1.5}}}).ok());
  auto before = this->store_->cached_features({"k1"});
  ASSERT_TRUE(before.ok()) << before.status().to_string();
  ASSERT_EQ(before->size(), 2u);
  std::string bytes = this->stored(StoredKind::kCachedValue).at("k1|volume").bytes;
  ASSERT_TRUE(cached_value_has_checksum(bytes));
  bytes[3] = char(bytes[3] ^ 0x10);  // a mantissa bit of the volume
  this->write_value("k1", "volume", bytes);
  auto after = this->store_->cached_features({"k1"});
  ASSERT_FALSE(after.ok());
  EXPECT_EQ(after.status().code(), StatusCode::kDataLoss);
  EXPECT_TRUE(contains(after.status().message(), "'volume' under key 'k1'")) << after.status().message();
  EXPECT_TRUE(contains(after.status().message(), "checksum mismatch")) << after.status().message();
  // The entry beside it is sound, and a read that does not ask for the damaged one gets it.
  auto other = this->store_->cached_features({"k1"}, {"area"});
  ASSERT_TRUE(other.ok()) << other.status().to_string();
  ASSERT_EQ(other->size(), 1u);
  EXPECT_EQ(other->at(0).value, std::vector<double>{1.5});
}

TYPED_TEST(StoreStoredBytes, ASurfaceBlobFlippedInPlaceIsRefusedAndAnUploadOfTheSameMeshRepairsIt) {
  const NewStructure s = new_structure("P1", "1.1", "s", 2);
  auto added = this->store_->add_structure(s);
  ASSERT_TRUE(added.ok());
  const std::string sha = added->structure.surface.sha256;
  std::string blob = *this->store_->get_surface_blob(sha);
  ASSERT_TRUE(decode_surface(blob).ok());
  blob[blob.size() / 2] = char(blob[blob.size() / 2] ^ 0x04);
  this->write_surface_blob(sha, blob);
  auto damaged = decode_surface(*this->store_->get_surface_blob(sha));
  ASSERT_FALSE(damaged.ok());
  EXPECT_EQ(damaged.status().code(), StatusCode::kDataLoss);
  EXPECT_TRUE(contains(damaged.status().message(), "checksum mismatch")) << damaged.status().message();

  auto again = this->store_->add_structure(new_structure("P1", "1.1", "s again", 2));
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  EXPECT_TRUE(again->surface_already_stored);
  EXPECT_EQ(*this->store_->get_surface_blob(sha), s.surface_blob);
  auto repaired = decode_surface(*this->store_->get_surface_blob(sha));
  ASSERT_TRUE(repaired.ok()) << repaired.status().to_string();
  EXPECT_EQ(surface_sha256(*repaired), sha);
}

TYPED_TEST(StoreStoredBytes, AnImageBlobFlippedInPlaceIsRefusedAndAnImportOfTheSameImageRepairsIt) {
  const NewSeries s = new_series("P1", "1.1", "1.1.1", 2.5f);
  ASSERT_TRUE(this->store_->put_series(s).ok());
  std::string blob = *this->store_->get_image_blob("1.1.1");
  blob[blob.size() - 1] = char(blob[blob.size() - 1] ^ 0x01);
  this->raw_.run("UPDATE image_blobs SET blob = ?1 WHERE sha256 = ?2", blob, {s.series.sha256});
  auto damaged = decode_image(*this->store_->get_image_blob("1.1.1"), s.series.geometry);
  ASSERT_FALSE(damaged.ok());
  EXPECT_EQ(damaged.status().code(), StatusCode::kDataLoss);

  ASSERT_TRUE(this->store_->put_series(s).ok());
  EXPECT_EQ(*this->store_->get_image_blob("1.1.1"), s.image_blob);
}

// What an older soiqd stored: surface blobs of version 2 and cached values without a checksum,
// under the schema version before this one. Opening the store re-encodes every blob whose mesh is
// still its sha256 (the same mesh, bit for bit) and gives every value its checksum; a version 2
// blob damaged already is left as it was, and the store still opens.
TYPED_TEST(StoreStoredBytes, AStoreOfTheSchemaBeforeChecksumsGetsThemWhenOpened) {
  std::map<std::string, TriangleMesh> meshes;
  std::string damaged_sha;
  for (int i = 0; i < 4; ++i) {
    const NewStructure s = new_structure("P1", "1.1", "s" + std::to_string(i), 10 * i);
    auto added = this->store_->add_structure(s);
    ASSERT_TRUE(added.ok());
    const std::string sha = added->structure.surface.sha256;
    meshes[sha] = *decode_surface(s.surface_blob);
    std::string v2 = std::string("SOIQSRF2", 8) + s.surface_blob.substr(12);
    if (i == 3) {
      // A flipped bit after which the blob still decodes, to another mesh: the silent case.
      bool silent = false;
      for (size_t at = 24; at < v2.size() && !silent; ++at) {
        v2[at] = char(v2[at] ^ 0x01);
        auto other = decode_surface(v2);
        silent = other.ok() && surface_sha256(*other) != sha;
        if (!silent) v2[at] = char(v2[at] ^ 0x01);
      }
      ASSERT_TRUE(silent);
      damaged_sha = sha;
    }
    this->write_surface_blob(sha, v2);
    ASSERT_TRUE(this->store_->put_cached_features(sha, {{"k" + std::to_string(i), "volume", {i + 0.5, -0.0}}}).ok());
  }
  for (const auto& [key, item] : this->stored(StoredKind::kCachedValue))
    this->write_value(item.key, item.entry, item.bytes.substr(0, item.bytes.size() - 4));
  this->raw_.set_schema_version(TypeParam::kBeforeChecksums);
  this->store_.reset();

  this->store_ = this->raw_.open();
  ASSERT_NE(this->store_, nullptr);
  const auto surfaces = this->stored(StoredKind::kSurface);
  ASSERT_EQ(surfaces.size(), 4u);
  for (const auto& [sha, item] : surfaces) {
    if (sha == damaged_sha) {
      EXPECT_EQ(surface_blob_version(item.bytes), 2) << "a damaged blob must not get a checksum";
      continue;
    }
    EXPECT_EQ(surface_blob_version(item.bytes), 3) << sha;
    auto mesh = decode_surface(item.bytes);
    ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
    EXPECT_EQ(mesh->triangles, meshes[sha].triangles);
    EXPECT_EQ(
        std::memcmp(mesh->vertices_mm.data(), meshes[sha].vertices_mm.data(), mesh->vertices_mm.size() * sizeof(Vec3)),
        0);
  }
  const auto values = this->stored(StoredKind::kCachedValue);
  ASSERT_EQ(values.size(), 4u);
  for (const auto& [key, item] : values) EXPECT_TRUE(cached_value_has_checksum(item.bytes)) << key;
  auto read = this->store_->cached_features({"k2"});
  ASSERT_TRUE(read.ok()) << read.status().to_string();
  ASSERT_EQ(read->size(), 1u);
  EXPECT_EQ(read->at(0).value, (std::vector<double>{2.5, -0.0}));
}

TYPED_TEST(StoreStoredBytes, AStoreOpenedReadOnlyIsLeftAsItIsAndRefusesWrites) {
  auto added = this->store_->add_structure(new_structure("P1", "1.1", "s", 1));
  ASSERT_TRUE(added.ok());
  const std::string sha = added->structure.surface.sha256;
  const std::string v3 = *this->store_->get_surface_blob(sha);
  this->write_surface_blob(sha, std::string("SOIQSRF2", 8) + v3.substr(12));
  this->raw_.set_schema_version(TypeParam::kBeforeChecksums);
  this->store_.reset();

  this->store_ = this->raw_.open(/*read_only=*/true);
  ASSERT_NE(this->store_, nullptr);
  EXPECT_EQ(surface_blob_version(this->stored(StoredKind::kSurface).at(sha).bytes), 2);
  const Status write = this->store_->add_structure(new_structure("P2", "2.1", "t", 5)).status();
  EXPECT_EQ(write.code(), StatusCode::kFailedPrecondition) << write.to_string();
  EXPECT_TRUE(contains(write.message(), "reading only")) << write.message();
  EXPECT_EQ(this->store_->counts()->structures, 1);
}

TYPED_TEST(StoreStoredBytes, ScanStoredVisitsEveryItemOnceWithItsUsers) {
  auto a = this->store_->add_structure(new_structure("P1", "1.1", "a", 1));
  auto b = this->store_->add_structure(new_structure("P1", "1.1", "b", 1));  // the same surface
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_TRUE(this->store_->put_series(new_series("P1", "1.1", "1.1.1", 2.5f)).ok());
  std::vector<CachedFeature> many;
  for (int i = 0; i < 1500; ++i)
    many.push_back({"k" + std::to_string(i / 10), "e" + std::to_string(i % 10), {1.0 * i}});
  ASSERT_TRUE(this->store_->put_cached_features(a->structure.surface.sha256, many).ok());

  const auto surfaces = this->stored(StoredKind::kSurface);
  ASSERT_EQ(surfaces.size(), 1u);
  EXPECT_EQ(surfaces.begin()->second.structure_ids, (std::vector<int64_t>{a->structure.id, b->structure.id}));
  const auto images = this->stored(StoredKind::kImage);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images.begin()->second.series_uid, "1.1.1");
  EXPECT_EQ(images.begin()->second.geometry.dims, (std::array<int64_t, 3>{3, 2, 2}));
  EXPECT_TRUE(decode_image(images.begin()->second.bytes, images.begin()->second.geometry).ok());
  const auto values = this->stored(StoredKind::kCachedValue);
  EXPECT_EQ(values.size(), 1500u);
  EXPECT_EQ(values.at("k42|e7").surface_sha256, a->structure.surface.sha256);
}

}  // namespace
}  // namespace soiq::db
