// The soiq-admin program itself (server/soiq_admin.cpp), run as an operator runs it, on stores of
// each real engine (tests/db/raw_store.h): `verify --db LOCATION` prints the counts and exits 0 on
// a sound store; on a store whose surface, image and cached value were damaged in place with SQL
// it names each and exits 1; a bad command line exits 2 saying why; --help tells of verify.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <type_traits>

#include "tests/db/raw_store.h"
#include "tests/db/temp_store.h"

namespace soiq::server {
namespace {

using db::testing::contains;
using db::testing::new_series;
using db::testing::new_structure;
using db::testing::TempDir;

struct AdminRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

AdminRun soiq_admin(const std::string& arguments) {
  AdminRun run;
  FILE* p = ::popen((std::string(SOIQ_ADMIN) + " " + arguments + " 2>&1").c_str(), "r");
  if (p == nullptr) return run;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) run.output.append(buffer, n);
  const int status = ::pclose(p);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// A location as an operator types it: the SQLite file's path, or a postgresql:// URI made of the
// test server's libpq key=value pairs.
std::string location_of(const db::testing::RawSqlite& raw) { return "'" + raw.location + "'"; }
std::string location_of(const db::testing::RawPostgres& raw) {
  auto value = [&](const std::string& key) {
    const size_t at = raw.location.find(key + "=") + key.size() + 1;
    return raw.location.substr(at, raw.location.find(' ', at) - at);
  };
  return "postgresql://" + value("user") + "@" + value("host") + ":" + value("port") + "/" + value("dbname");
}

template <typename Raw>
class SoiqAdminVerify : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = raw_.open();
    ASSERT_NE(store_, nullptr);
    auto added = store_->add_structure(new_structure("P1", "1.1", "a", 1));
    ASSERT_TRUE(added.ok());
    id_ = added->structure.id;
    sha_ = added->structure.surface.sha256;
    ASSERT_TRUE(store_->put_cached_features(sha_, {{"k1", "volume", {1.5}}, {"k1", "area", {2.5}}}).ok());
    series_ = new_series("P1", "1.1", "1.1.7", 3.5f);
    ASSERT_TRUE(store_->put_series(series_).ok());
  }

  TempDir dir_;
  Raw raw_{dir_};
  std::unique_ptr<db::SqlStore> store_;
  int64_t id_ = 0;
  std::string sha_;
  db::NewSeries series_;
};

TYPED_TEST_SUITE(SoiqAdminVerify, db::testing::RawBackends, db::testing::StoreBackendNames);

TYPED_TEST(SoiqAdminVerify, ASoundStoreExitsZeroWithTheCounts) {
  const AdminRun run = soiq_admin("verify --db " + location_of(this->raw_));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "surfaces")) << run.output;
  EXPECT_TRUE(contains(run.output, "1 checked")) << run.output;  // the surface, the image
  EXPECT_TRUE(contains(run.output, "2 checked")) << run.output;  // the cached values
  EXPECT_TRUE(contains(run.output, "the store is sound")) << run.output;
}

TYPED_TEST(SoiqAdminVerify, ADamagedStoreExitsOneNamingTheDamagedSurfaceImageAndCachedValue) {
  std::string blob = *this->store_->get_surface_blob(this->sha_);
  blob[20] = char(blob[20] ^ 0x01);  // the triangle count
  this->raw_.run("UPDATE surfaces SET blob = ?1 WHERE sha256 = ?2", blob, {this->sha_});
  std::string image = this->series_.image_blob;
  image[image.size() / 2] = char(image[image.size() / 2] ^ 0x80);
  this->raw_.run("UPDATE image_blobs SET blob = ?1 WHERE sha256 = ?2", image, {this->series_.series.sha256});
  const std::vector<double> wrong = {1.75};  // a value, its checksum kept: as if a bit flipped
  std::string value(reinterpret_cast<const char*>(wrong.data()), 8);
  value += std::string(4, '\x5a');
  this->raw_.run("UPDATE feature_cache SET value = ?1 WHERE key = ?2 AND entry = ?3", value, {"k1", "volume"});

  const AdminRun run = soiq_admin("verify --db " + location_of(this->raw_));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "damaged surface " + this->sha_ + " (structure " + std::to_string(this->id_) +
                                       "): surface blob checksum mismatch"))
      << run.output;
  EXPECT_TRUE(contains(run.output, "damaged image " + this->series_.series.sha256 + " (series 1.1.7)")) << run.output;
  EXPECT_TRUE(contains(run.output, "damaged cached value 'volume' under key 'k1' (surface " + this->sha_ +
                                       ", structure " + std::to_string(this->id_) + "): checksum mismatch"))
      << run.output;
  EXPECT_FALSE(contains(run.output, "'area'")) << run.output;
  EXPECT_TRUE(contains(run.output, "3 damaged")) << run.output;
}

TEST(SoiqAdmin, ABadCommandLineExitsTwoSayingWhy) {
  for (const auto& [arguments, why] : {std::pair{"verify", "verify needs --db"},
                                       std::pair{"verify --db x.db --to y.db", "verify takes --db, not --to"},
                                       std::pair{"verify --db", "'--db' needs a value"},
                                       std::pair{"frobnicate", "the commands are migrate, backup and verify"},
                                       std::pair{"verify --db mysql://x/y", "postgresql://"}}) {
    const AdminRun run = soiq_admin(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << ": " << run.output;
    EXPECT_TRUE(contains(run.output, why)) << arguments << ": " << run.output;
  }
}

TEST(SoiqAdmin, AStoreThatIsNotThereIsAFailureNotAnEmptyReport) {
  TempDir dir;
  const AdminRun run = soiq_admin("verify --db " + dir.file("missing.db"));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "missing.db")) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("missing.db"))) << "verify must not create a store";
}

TEST(SoiqAdmin, HelpTellsOfVerify) {
  const AdminRun run = soiq_admin("--help");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "soiq-admin verify --db LOCATION")) << run.output;
  EXPECT_TRUE(contains(run.output, "Exit codes")) << run.output;
}

}  // namespace
}  // namespace soiq::server
