// The kept DICOM instances' stored bytes on each real engine (raw_store.h): a file or a row changed
// in place with SQL (a failing disk) is DATA_LOSS naming it, never read as other bytes, and an
// import of the same series repairs it; soiq-admin verify's scan hands them out as stored; a copy to
// the other backend (soiq-admin migrate) keeps them; a SQLite file of the schema before them is
// read as it is, and migrated keeping its series.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "db/sqlite/schema_migrations.h"
#include "tests/db/raw_store.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::series_with_instances;
using testing::slice_uid;
using testing::TempDir;

constexpr char kDamagedSeries[] = "1.2.3.4";

template <typename Raw>
class StoreInstancesDamage : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = raw_.open();
    ASSERT_NE(store_, nullptr);
    ASSERT_TRUE(store_->put_series(sent_).ok());
  }

  // list_instances' error, or "" when it lists the series' instances as they were sent.
  std::string list_error() {
    auto got = store_->list_instances(kDamagedSeries);
    if (!got.ok()) return got.status().to_string();
    EXPECT_EQ(got->size(), sent_.instances.size());
    for (size_t k = 0; k < got->size() && k < sent_.instances.size(); ++k) {
      EXPECT_EQ((*got)[k].metadata, sent_.instances[k].record.metadata);
      EXPECT_EQ((*got)[k].slice, sent_.instances[k].record.slice);
    }
    return "";
  }

  TempDir dir_;
  Raw raw_{dir_};
  std::unique_ptr<SqlStore> store_;
  const NewSeries sent_ = series_with_instances("P1", kDamagedSeries, 1.0f);
};

TYPED_TEST_SUITE(StoreInstancesDamage, testing::RawBackends, testing::StoreBackendNames);

TYPED_TEST(StoreInstancesDamage, AFlippedByteInAFileIsDataLossUntilTheSeriesIsImportedAgain) {
  const NewInstance& hit = this->sent_.instances[1];
  std::string bytes = hit.file;
  bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x08);
  this->raw_.run("UPDATE instance_files SET blob = ?1 WHERE sha256 = ?2", bytes, {hit.record.file_sha256});
  const auto damaged = this->store_->get_instance_file(hit.record.file_sha256);
  ASSERT_EQ(damaged.status().code(), StatusCode::kDataLoss) << damaged.status().to_string();
  EXPECT_TRUE(contains(damaged.status().message(), "instance file " + hit.record.file_sha256 + " is damaged"))
      << damaged.status().message();
  EXPECT_TRUE(contains(damaged.status().message(), "import the series again")) << damaged.status().message();
  EXPECT_EQ(*this->store_->get_instance_file(this->sent_.instances[0].record.file_sha256),
            this->sent_.instances[0].file);

  NewSeries again = this->sent_;
  again.replace_other_content = false;
  ASSERT_TRUE(this->store_->put_series(again).ok());
  const auto repaired = this->store_->get_instance_file(hit.record.file_sha256);
  ASSERT_TRUE(repaired.ok()) << repaired.status().to_string();
  EXPECT_EQ(*repaired, hit.file);
}

TYPED_TEST(StoreInstancesDamage, ADamagedRowIsDataLossNamingTheInstanceUntilTheSeriesIsImportedAgain) {
  const std::string uid = slice_uid(kDamagedSeries, 2);
  std::string metadata = this->sent_.instances[2].record.metadata;
  metadata[metadata.size() - 4] = 'X';
  const std::vector<std::string> damages = {
      "UPDATE instances SET metadata_crc32 = metadata_crc32 + 1 WHERE sop_instance_uid = ?2",
      "UPDATE instances SET slice = 0 WHERE sop_instance_uid = ?2",
      "UPDATE instances SET metadata = '" + metadata + "' WHERE sop_instance_uid = ?2",
  };
  ASSERT_EQ(this->list_error(), "");
  for (const std::string& damage : damages) {
    this->raw_.run(damage, {}, {uid});
    const std::string error = this->list_error();
    EXPECT_TRUE(contains(error, "DATA_LOSS")) << damage << ": " << error;
    EXPECT_TRUE(contains(error, "instance '" + uid + "' of series '1.2.3.4' is damaged")) << damage << ": " << error;
    ASSERT_TRUE(this->store_->put_series(this->sent_).ok());
    EXPECT_EQ(this->list_error(), "") << damage;
  }
}

// soiq-admin verify's scan (SqlStore::scan_stored) hands out each file and each row as stored, for
// the file's sha256 and the row's checksum to be checked again.
TYPED_TEST(StoreInstancesDamage, TheScanHandsOutEachFileAndRowAsStored) {
  std::map<std::string, StoredItem> files, rows;
  for (const auto& scan : {std::pair{StoredKind::kInstanceFile, &files}, std::pair{StoredKind::kInstance, &rows}}) {
    // Not a structured binding: clang 14 (the sanitizer build) cannot capture one in a lambda.
    const StoredKind kind = scan.first;
    std::map<std::string, StoredItem>* into = scan.second;
    ASSERT_TRUE(this->store_
                    ->scan_stored(kind,
                                  [&](const StoredItem& item) {
                                    EXPECT_EQ(into->count(item.key), 0u) << item.key << " visited twice";
                                    (*into)[item.key] = item;
                                    return ok_status();
                                  })
                    .ok());
  }
  ASSERT_EQ(files.size(), 3u);
  ASSERT_EQ(rows.size(), 3u);
  for (const NewInstance& i : this->sent_.instances) {
    const StoredItem& file = files.at(i.record.file_sha256);
    EXPECT_EQ(file.bytes, i.file);
    EXPECT_EQ(file.series_uid, kDamagedSeries);
    const StoredItem& row = rows.at(i.record.sop_instance_uid);
    EXPECT_EQ(row.series_uid, kDamagedSeries);
    EXPECT_EQ(row.instance.metadata, i.record.metadata);
    EXPECT_EQ(row.instance_crc32, int64_t(instance_row_crc32(i.record)));
  }
}

TEST(StoreInstancesCopy, ACopyToPostgresKeepsTheInstancesTheirFilesAndTheirDigests) {
  TempDir dir;
  const testing::RawSqlite from(dir);
  const testing::RawPostgres to(dir);
  auto source = from.open();
  auto target = to.open();
  ASSERT_TRUE(source && target);
  const NewSeries s = series_with_instances("P1", kDamagedSeries, 1.0f);
  ASSERT_TRUE(source->put_series(s).ok());
  ASSERT_TRUE(source->copy_to(*target, {}).ok());
  const auto want = source->table_digests();
  const auto got = target->table_digests();
  ASSERT_TRUE(want.ok() && got.ok());
  ASSERT_EQ(want->size(), got->size());
  int instance_tables = 0;
  for (size_t i = 0; i < want->size(); ++i) {
    EXPECT_EQ((*want)[i].sha256, (*got)[i].sha256) << (*want)[i].table;
    if ((*want)[i].table == "instances" || (*want)[i].table == "instance_files") {
      EXPECT_EQ((*got)[i].rows, 3) << (*want)[i].table;
      ++instance_tables;
    }
  }
  EXPECT_EQ(instance_tables, 2);
  const auto listed = target->list_instances(kDamagedSeries);
  ASSERT_TRUE(listed.ok()) << listed.status().to_string();  // the checksums hold on the other engine
  ASSERT_EQ(listed->size(), 3u);
  EXPECT_EQ(*target->get_instance_file(listed->at(1).file_sha256), s.instances[1].file);
}

TEST(SqliteStoreInstances, AFileOfSchemaTenIsMigratedKeepingItsSeries) {
  TempDir dir;
  const std::string path = dir.file("v10.db");
  {
    auto store = testing::open_store(path);
    ASSERT_TRUE(store->put_series(series_with_instances("P1", kDamagedSeries, 1.0f, /*kept=*/false)).ok());
  }
  testing::exec_sql(path, std::string(testing::kBackToSchemaV10) + "PRAGMA user_version = 10");
  {
    // Read only, as it is: no instances, and counts and digests read the missing tables as empty.
    SqliteOptions options;
    options.read_only = true;
    auto old = SqliteStore::open(path, options);
    ASSERT_TRUE(old.ok()) << old.status().to_string();
    EXPECT_EQ(*(*old)->schema_version(), 10);
    EXPECT_EQ((*old)->counts()->instances, 0);
    EXPECT_TRUE((*old)->table_digests().ok());
    int scanned = 0;
    for (const StoredKind kind : {StoredKind::kInstanceFile, StoredKind::kInstance}) {
      const Status s = (*old)->scan_stored(kind, [&](const StoredItem&) {
        ++scanned;
        return ok_status();
      });
      EXPECT_TRUE(s.ok()) << s.to_string();
    }
    EXPECT_EQ(scanned, 0);
  }
  auto store = testing::open_store(path);
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  ASSERT_TRUE(store->get_series(kDamagedSeries).ok());
  auto none = store->list_instances(kDamagedSeries);
  ASSERT_TRUE(none.ok()) << none.status().to_string();
  EXPECT_TRUE(none->empty());
  // Imported again with its instances, the series gets them.
  NewSeries again = series_with_instances("P1", kDamagedSeries, 1.0f);
  again.replace_other_content = false;
  ASSERT_TRUE(store->put_series(again).ok());
  EXPECT_EQ(store->list_instances(kDamagedSeries)->size(), 3u);
}

}  // namespace
}  // namespace soiq::db
