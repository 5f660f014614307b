// soiq-admin's work on stores: a migration SQLite -> PostgreSQL -> SQLite keeps every record, key
// and byte (the digests of the three stores agree, ids included, and new ids follow the copied
// ones), refuses a target that holds records, and a backup of a SQLite store is the same store.
#include "server/app/store_admin.h"

#include <gtest/gtest.h>

#include "tests/db/store_backends.h"
#include "tests/db/temp_store.h"

namespace soiq::server {
namespace {

using db::testing::new_series;
using db::testing::new_structure;

// A store with a bit of everything: patients with studies, series (images), structures sharing a
// surface, cached features, a precomputed structure and queued ones.
void fill(db::Store& store) {
  ASSERT_TRUE(store.put_series(new_series("P1", "1.1", "1.1.1", 2.5f)).ok());
  for (int i = 0; i < 5; ++i) {
    db::NewStructure s = new_structure(i < 3 ? "P1" : "P2", i < 3 ? "1.1" : "2.1", "s" + std::to_string(i), i % 3);
    s.patient.sex = i < 3 ? "F" : "M";
    s.patient.birth_date = "19700101";
    s.study.study_date = "20200615";
    s.laterality = i % 2 ? "L" : "R";
    auto added = store.add_structure(s);
    ASSERT_TRUE(added.ok()) << added.status().to_string();
    ASSERT_TRUE(store
                    .put_cached_features(added->structure.surface.sha256,
                                         {{"k" + std::to_string(i), "volume", {1.0 / 3.0 + i, -0.0}}})
                    .ok());
  }
  auto queue = store.precompute_queue(1);
  ASSERT_TRUE(queue.ok() && !queue->empty());
  db::Precomputed p;
  p.structure_id = queue->front().id;
  p.surface_sha256 = queue->front().surface.sha256;
  p.definitions_version = 3;
  p.values = {1.5, 2.5, 0.75, std::nullopt, 0.5, 3.25};
  ASSERT_TRUE(store.put_precomputed(p).ok());
}

TEST(StoreAdmin, AMigrationToPostgresAndBackKeepsEveryRecordKeyAndByte) {
  db::testing::TempDir dir;
  const StoreLocation sqlite{StoreLocation::Kind::kSqlite, dir.file("a.db")};
  {
    auto store = open_store(sqlite, {});
    ASSERT_TRUE(store.ok());
    fill(**store);
  }
  const std::string conninfo = db::testing::fresh_postgres_database();
  ASSERT_FALSE(conninfo.empty());
  const StoreLocation postgres{StoreLocation::Kind::kPostgres, conninfo};
  auto there = migrate_store(sqlite, postgres, {});
  ASSERT_TRUE(there.ok()) << there.status().to_string();
  const StoreLocation back{StoreLocation::Kind::kSqlite, dir.file("b.db")};
  auto again = migrate_store(postgres, back, {});
  ASSERT_TRUE(again.ok()) << again.status().to_string();
  ASSERT_EQ(there->size(), again->size());
  for (size_t i = 0; i < there->size(); ++i) {
    EXPECT_EQ((*there)[i].rows, (*again)[i].rows) << (*there)[i].table;
    EXPECT_EQ((*there)[i].sha256, (*again)[i].sha256) << (*there)[i].table;
  }
  EXPECT_EQ(there->front().table, "patients");
  EXPECT_EQ(there->front().rows, 2);

  // The copy serves: the same ids, and a new structure gets the next one.
  auto pg = open_store(postgres, {});
  ASSERT_TRUE(pg.ok());
  auto listed = (*pg)->list_structures({}, {});
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->items.size(), 5u);
  const int64_t last = listed->items.back().id;
  auto added = (*pg)->add_structure(new_structure("P3", "3.1", "new", 9));
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  EXPECT_EQ(added->structure.id, last + 1);

  // A target with records is refused, and keeps them.
  auto refused = migrate_store(sqlite, postgres, {});
  EXPECT_EQ(refused.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ((*pg)->counts()->structures, 6);
}

TEST(StoreAdmin, ABackupOfASqliteStoreIsTheSameStore) {
  db::testing::TempDir dir;
  const StoreLocation live{StoreLocation::Kind::kSqlite, dir.file("live.db")};
  auto store = open_store(live, {});  // open while backed up, as soiqd would be
  ASSERT_TRUE(store.ok());
  fill(**store);
  ASSERT_TRUE(backup_store(live, dir.file("copy.db")).ok());
  auto a = open_sql_store(live, {});
  auto b = open_sql_store({StoreLocation::Kind::kSqlite, dir.file("copy.db")}, {});
  ASSERT_TRUE(a.ok() && b.ok());
  auto da = (*a)->table_digests();
  auto db_ = (*b)->table_digests();
  ASSERT_TRUE(da.ok() && db_.ok());
  ASSERT_EQ(da->size(), db_->size());
  for (size_t i = 0; i < da->size(); ++i) EXPECT_EQ((*da)[i].sha256, (*db_)[i].sha256) << (*da)[i].table;
}

TEST(StoreAdmin, ABackupOfPostgresOrANonDatabaseIsRefusedSayingWhy) {
  db::testing::TempDir dir;
  const Status pg = backup_store({StoreLocation::Kind::kPostgres, "postgresql://x@127.0.0.1:1/x"}, dir.file("c.db"));
  EXPECT_EQ(pg.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(pg.message().find("pg_dump"), std::string::npos);
  const std::string junk = dir.file("junk.db");
  {
    std::FILE* f = std::fopen(junk.c_str(), "w");
    std::fputs("not a database, only text that is long enough to look like a header", f);
    std::fclose(f);
  }
  const Status bad = backup_store({StoreLocation::Kind::kSqlite, junk}, dir.file("d.db"));
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("junk.db"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace soiq::server
