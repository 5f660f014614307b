// soiq-admin verify's scrub (server/app/store_verify.h) on each real engine (tests/db/raw_store.h):
// a sound store is reported sound with the count of each kind (the store's own counts); a surface,
// an image and a cached value damaged in place with SQL, and a surface blob stored under another
// mesh's key, and a kept DICOM file and instance damaged in place, are each named with what is
// wrong and who uses it; blobs an older soiqd stored without a checksum are listed, and the store
// is left as it was (read only, not migrated).
#include "server/app/store_verify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <type_traits>

#include "db/surface_blob.h"
#include "tests/db/raw_store.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::new_series;
using db::testing::new_structure;
using db::testing::TempDir;

template <typename Raw>
class StoreVerify : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = raw_.open();
    ASSERT_NE(store_, nullptr);
    // Two surfaces, one of them shared by two structures; two images; cached values of both.
    for (const auto& [name, offset] : {std::pair{"a", 1.0}, std::pair{"b", 2.0}, std::pair{"b again", 2.0}}) {
      auto added = store_->add_structure(new_structure("P1", "1.1", name, offset));
      ASSERT_TRUE(added.ok()) << added.status().to_string();
      ids_.push_back(added->structure.id);
      shas_.push_back(added->structure.surface.sha256);
      ASSERT_TRUE(store_->put_cached_features(shas_.back(), {{"k" + shas_.back(), "volume", {offset}}}).ok());
    }
    for (const char* uid : {"1.1.1", "1.1.2"}) {
      series_.push_back(new_series("P1", "1.1", uid, uid[4] == '1' ? 1.5f : 2.5f));
      ASSERT_TRUE(store_->put_series(series_.back()).ok());
    }
  }

  StoreLocation location() const {
    return {
        std::is_same_v<Raw, db::testing::RawPostgres> ? StoreLocation::Kind::kPostgres : StoreLocation::Kind::kSqlite,
        raw_.location};
  }

  VerifyReport verify() {
    Result<VerifyReport> r = verify_store(location(), {});
    EXPECT_TRUE(r.ok()) << r.status().to_string();
    return r.ok() ? *r : VerifyReport{};
  }

  TempDir dir_;
  Raw raw_{dir_};
  std::unique_ptr<db::SqlStore> store_;
  std::vector<int64_t> ids_;
  std::vector<std::string> shas_;
  std::vector<db::NewSeries> series_;
};

TYPED_TEST_SUITE(StoreVerify, db::testing::RawBackends, db::testing::StoreBackendNames);

const VerifyFinding* find(const std::vector<VerifyFinding>& all, const std::string& kind) {
  auto it = std::find_if(all.begin(), all.end(), [&](const VerifyFinding& f) { return f.kind == kind; });
  return it == all.end() ? nullptr : &*it;
}

TYPED_TEST(StoreVerify, ASoundStoreIsReportedSoundWithTheCountOfEachKind) {
  const VerifyReport r = this->verify();
  const db::Counts counts = *this->store_->counts();
  EXPECT_TRUE(r.sound());
  EXPECT_EQ(r.surfaces.checked, counts.surfaces);
  EXPECT_EQ(r.images.checked, int64_t(this->series_.size()));
  EXPECT_EQ(r.cached_values.checked, counts.cached_features);
  EXPECT_EQ(r.surfaces.damaged + r.images.damaged + r.cached_values.damaged, 0);
  EXPECT_EQ(r.surfaces.without_checksum + r.images.without_checksum + r.cached_values.without_checksum, 0);
  const std::vector<std::string> lines = format_verify_report(r);
  ASSERT_EQ(lines.size(), 6u);  // a line per kind, then the verdict
  EXPECT_TRUE(contains(lines[0], "surfaces")) << lines[0];
  EXPECT_TRUE(contains(lines[0], std::to_string(counts.surfaces) + " checked")) << lines[0];
  EXPECT_EQ(lines.back(), "the store is sound");
}

TYPED_TEST(StoreVerify, EachDamagedSurfaceImageAndCachedValueIsNamedWithWhatIsWrong) {
  // Surface b (shared by two structures): one bit of its blob.
  std::string blob = *this->store_->get_surface_blob(this->shas_[1]);
  blob[blob.size() / 2] = char(blob[blob.size() / 2] ^ 0x20);
  this->raw_.run("UPDATE surfaces SET blob = ?1 WHERE sha256 = ?2", blob, {this->shas_[1]});
  // Image 1.1.2: one bit of its voxels' stream.
  std::string image = this->series_[1].image_blob;
  image.back() = char(image.back() ^ 0x02);
  this->raw_.run("UPDATE image_blobs SET blob = ?1 WHERE sha256 = ?2", image, {this->series_[1].series.sha256});
  // Surface a's cached value: one bit.
  ASSERT_TRUE(this->store_
                  ->scan_stored(db::StoredKind::kCachedValue,
                                [&](const db::StoredItem& item) {
                                  if (item.surface_sha256 != this->shas_[0]) return ok_status();
                                  std::string bytes = item.bytes;
                                  bytes[0] = char(bytes[0] ^ 0x01);
                                  this->raw_.run("UPDATE feature_cache SET value = ?1 WHERE key = ?2 AND entry = ?3",
                                                 bytes, {item.key, item.entry});
                                  return ok_status();
                                })
                  .ok());

  const VerifyReport r = this->verify();
  EXPECT_FALSE(r.sound());
  EXPECT_EQ(r.surfaces.checked, 2);
  EXPECT_EQ(r.surfaces.damaged, 1);
  EXPECT_EQ(r.images.damaged, 1);
  EXPECT_EQ(r.cached_values.damaged, 1);
  ASSERT_EQ(r.damaged.size(), 3u);
  const VerifyFinding* surface = find(r.damaged, "surface");
  ASSERT_NE(surface, nullptr);
  EXPECT_EQ(surface->id, this->shas_[1]);
  EXPECT_EQ(surface->users, "structures " + std::to_string(this->ids_[1]) + ", " + std::to_string(this->ids_[2]));
  EXPECT_TRUE(contains(surface->problem, "checksum mismatch")) << surface->problem;
  const VerifyFinding* image_finding = find(r.damaged, "image");
  ASSERT_NE(image_finding, nullptr);
  EXPECT_EQ(image_finding->id, this->series_[1].series.sha256);
  EXPECT_EQ(image_finding->users, "series 1.1.2");
  const VerifyFinding* value = find(r.damaged, "cached value");
  ASSERT_NE(value, nullptr);
  EXPECT_EQ(value->id, "'volume' under key 'k" + this->shas_[0] + "'");
  EXPECT_EQ(value->users, "surface " + this->shas_[0] + ", structure " + std::to_string(this->ids_[0]));
  EXPECT_TRUE(contains(value->problem, "checksum mismatch")) << value->problem;

  const std::vector<std::string> lines = format_verify_report(r);
  EXPECT_TRUE(contains(lines.back(), "3 damaged")) << lines.back();
  EXPECT_EQ(std::count_if(lines.begin(), lines.end(), [](const std::string& l) { return l.rfind("damaged ", 0) == 0; }),
            3);
}

// A sound blob stored under another mesh's key (its checksum holds) is found by its sha256.
TYPED_TEST(StoreVerify, ASurfaceBlobStoredUnderAnotherMeshsKeyIsDamaged) {
  const std::string other = *this->store_->get_surface_blob(this->shas_[1]);
  this->raw_.run("UPDATE surfaces SET blob = ?1 WHERE sha256 = ?2", other, {this->shas_[0]});
  const VerifyReport r = this->verify();
  ASSERT_EQ(r.damaged.size(), 1u);
  EXPECT_EQ(r.damaged[0].id, this->shas_[0]);
  EXPECT_TRUE(contains(r.damaged[0].problem, "decodes to a mesh of sha256 " + this->shas_[1])) << r.damaged[0].problem;
}

// What an older soiqd stored (a version 2 blob, values without a checksum, the schema before):
// listed and counted, and left as it is: verify neither migrates nor writes.
TYPED_TEST(StoreVerify, BytesWithoutAChecksumAreListedAndTheStoreIsLeftAsItIs) {
  const std::string v3 = *this->store_->get_surface_blob(this->shas_[0]);
  this->raw_.run("UPDATE surfaces SET blob = ?1 WHERE sha256 = ?2", "SOIQSRF2" + v3.substr(12), {this->shas_[0]});
  this->raw_.run("UPDATE feature_cache SET value = ?1 WHERE key = ?2", std::string(8, '\0'), {"k" + this->shas_[1]});
  this->raw_.set_schema_version(TypeParam::kBeforeChecksums);
  const std::vector<db::TableDigest> before = *this->store_->table_digests();

  const VerifyReport r = this->verify();
  EXPECT_TRUE(r.sound());
  EXPECT_EQ(r.surfaces.without_checksum, 1);
  EXPECT_EQ(r.cached_values.without_checksum, 1);
  const VerifyFinding* surface = find(r.without_checksum, "surface");
  ASSERT_NE(surface, nullptr);
  EXPECT_EQ(surface->id, this->shas_[0]);
  EXPECT_TRUE(contains(surface->problem, "version 2")) << surface->problem;

  const std::vector<db::TableDigest> after = *this->store_->table_digests();
  ASSERT_EQ(before.size(), after.size());
  for (size_t i = 0; i < before.size(); ++i) EXPECT_EQ(before[i].sha256, after[i].sha256) << before[i].table;
  EXPECT_EQ(db::surface_blob_version(*this->store_->get_surface_blob(this->shas_[0])), 2);
}

// The kept DICOM instances (db::InstanceRecord): a file whose bytes no longer hash to its key, and
// a record whose checksum fails, are each named with the series that holds it.
TYPED_TEST(StoreVerify, ADamagedInstanceFileAndADamagedInstanceAreNamed) {
  const db::NewSeries s = db::testing::series_with_instances("P2", "2.1.1", 3.0f);
  ASSERT_TRUE(this->store_->put_series(s).ok());
  std::string file = s.instances[0].file;
  file.back() = char(file.back() ^ 0x40);
  this->raw_.run("UPDATE instance_files SET blob = ?1 WHERE sha256 = ?2", file, {s.instances[0].record.file_sha256});
  this->raw_.run("UPDATE instances SET slice = 2 WHERE sop_instance_uid = ?2", {}, {"2.1.1.2"});

  const VerifyReport r = this->verify();
  EXPECT_EQ(r.instance_files.checked, 3);
  EXPECT_EQ(r.instances.checked, 3);
  EXPECT_EQ(r.instance_files.damaged, 1);
  EXPECT_EQ(r.instances.damaged, 1);
  const VerifyFinding* damaged_file = find(r.damaged, "instance file");
  ASSERT_NE(damaged_file, nullptr);
  EXPECT_EQ(damaged_file->id, s.instances[0].record.file_sha256);
  EXPECT_EQ(damaged_file->users, "series 2.1.1");
  const VerifyFinding* instance = find(r.damaged, "instance");
  ASSERT_NE(instance, nullptr);
  EXPECT_EQ(instance->id, "2.1.1.2");
  EXPECT_TRUE(contains(instance->problem, "checksum")) << instance->problem;
}

TYPED_TEST(StoreVerify, AStoreOfANewerSchemaIsRefused) {
  this->raw_.set_schema_version(TypeParam::kBeforeChecksums + 100);
  const Result<VerifyReport> r = verify_store(this->location(), {});
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition) << r.status().to_string();
  EXPECT_TRUE(contains(r.status().message(), "newer")) << r.status().message();
}

}  // namespace
}  // namespace soiq::server
