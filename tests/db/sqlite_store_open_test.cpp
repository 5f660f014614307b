// Opening a SqliteStore: schema creation and migration, refusals, persistence, durability.
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/voxelize/memory_estimate.h"
#include "db/deflate.h"
#include "db/sqlite/schema_migrations.h"
#include "db/sqlite/sqlite_store.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::new_structure;
using testing::open_store;
using testing::TempDir;

void set_user_version(const std::string& path, int version) {
  testing::exec_sql(path, "PRAGMA user_version = " + std::to_string(version));
}

TEST(SqliteStoreOpen, NewFileGetsTheLatestSchemaInWalMode) {
  TempDir dir;
  auto store = open_store(dir.file("new.db"));
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  auto n = store->counts();
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n->patients + n->studies + n->series + n->structures + n->surfaces + n->cached_features, 0);
  store.reset();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir.file("new.db").c_str(), &db), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &st, nullptr);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), "wal");
  sqlite3_finalize(st);
  sqlite3_close(db);
}

TEST(SqliteStoreOpen, EmptyExistingFileIsMigratedFromVersionZero) {
  TempDir dir;
  std::ofstream(dir.file("empty.db")).close();  // zero bytes: a valid, empty SQLite database
  auto store = open_store(dir.file("empty.db"));
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
}

TEST(SqliteStoreOpen, DataPersistsAcrossCloseAndReopen) {
  TempDir dir;
  int64_t id = 0;
  {
    auto store = open_store(dir.file("p.db"));
    auto added = store->add_structure(new_structure("P1", "1.2.3", "Hippocampus"));
    ASSERT_TRUE(added.ok()) << added.status().to_string();
    id = added->structure.id;
    ASSERT_TRUE(store->put_cached_features(added->structure.surface.sha256, {{"k", "volume", {1.5, -0.0}}}).ok());
  }
  auto store = open_store(dir.file("p.db"));
  auto s = store->get_structure(id);
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  EXPECT_EQ(s->name, "Hippocampus");
  EXPECT_EQ(s->patient_id, "P1");
  auto cached = store->cached_features({"k"});
  ASSERT_TRUE(cached.ok());
  ASSERT_EQ(cached->size(), 1u);
  EXPECT_EQ((*cached)[0].value, (std::vector<double>{1.5, -0.0}));
}

// A store of schema version 3 holds zlib surface blobs; opening it with this code re-encodes each
// in version 2, and the structure's surface reads back exactly as before.
TEST(SqliteStoreOpen, Version3SurfaceBlobsAreReencodedByTheMigration) {
  TempDir dir;
  const std::string path = dir.file("v3.db");
  std::string sha;
  {
    auto store = open_store(path);
    auto added = store->add_structure(new_structure("P1", "1.2.3", "Hippocampus", 2.5));
    ASSERT_TRUE(added.ok()) << added.status().to_string();
    sha = added->structure.surface.sha256;
  }
  const TriangleMesh mesh = testing::tetrahedron(2.5);
  // What a version 3 store holds: the canonical bytes (32-byte header, payload) deflated.
  std::string canonical("SOIQSURF", 8);
  const uint32_t version = 1, reserved = 0;
  const uint64_t nv = mesh.vertices_mm.size(), nt = mesh.triangles.size();
  canonical.append(reinterpret_cast<const char*>(&version), 4).append(reinterpret_cast<const char*>(&reserved), 4);
  canonical.append(reinterpret_cast<const char*>(&nv), 8).append(reinterpret_cast<const char*>(&nt), 8);
  canonical.append(reinterpret_cast<const char*>(mesh.vertices_mm.data()), nv * sizeof(Vec3));
  canonical.append(reinterpret_cast<const char*>(mesh.triangles.data()), nt * 12);
  const std::string v1 = *deflate_bytes(canonical.data(), canonical.size());
  ASSERT_EQ(sha256_hex(canonical.data(), canonical.size()), sha);
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, "UPDATE surfaces SET blob = ? WHERE sha256 = ?", -1, &st, nullptr), SQLITE_OK);
    sqlite3_bind_blob(st, 1, v1.data(), int(v1.size()), SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 2, sha.c_str(), -1, SQLITE_TRANSIENT);
    ASSERT_EQ(sqlite3_step(st), SQLITE_DONE);
    sqlite3_finalize(st);
    ASSERT_EQ(sqlite3_exec(db, (std::string(testing::kBackToSchemaV3) + "PRAGMA user_version = 3").c_str(), nullptr,
                           nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
  }
  auto store = open_store(path);
  ASSERT_TRUE(store);
  EXPECT_EQ(*store->schema_version(), latest_schema_version());
  auto blob = store->get_surface_blob(sha);
  ASSERT_TRUE(blob.ok()) << blob.status().to_string();
  EXPECT_FALSE(is_deflated_surface_blob(*blob));
  auto back = decode_surface(*blob);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_EQ(back->triangles, mesh.triangles);
  EXPECT_EQ(std::memcmp(back->vertices_mm.data(), mesh.vertices_mm.data(), nv * sizeof(Vec3)), 0);
  // The measure the memory budget needs was computed by the migration, and is stored with new
  // surfaces too.
  const SurfaceMeasure measure = surface_measure(mesh);
  ASSERT_GT(measure.area_mm2, 0);
  auto migrated = store->list_structures(StructureFilter{}, PageRequest{});
  ASSERT_TRUE(migrated.ok());
  ASSERT_EQ(migrated->items.size(), 1u);
  EXPECT_EQ(migrated->items[0].surface.area_bound_mm2, measure.area_mm2);
  EXPECT_EQ(migrated->items[0].surface.perimeter_bound_mm, measure.perimeter_mm);
  auto added = store->add_structure(new_structure("P2", "2.2", "Amygdala", 7.5));
  ASSERT_TRUE(added.ok());
  auto fresh = store->get_structure(added->structure.id);
  ASSERT_TRUE(fresh.ok());
  EXPECT_EQ(fresh->surface.area_bound_mm2, surface_measure(testing::tetrahedron(7.5)).area_mm2);
  EXPECT_GT(fresh->surface.perimeter_bound_mm, 0);
}

TEST(SqliteStoreOpen, NewerSchemaVersionIsRefusedNamingBothVersions) {
  TempDir dir;
  { open_store(dir.file("future.db")); }
  set_user_version(dir.file("future.db"), latest_schema_version() + 5);
  auto store = SqliteStore::open(dir.file("future.db"), {});
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kFailedPrecondition);
  const std::string& m = store.status().message();
  EXPECT_TRUE(contains(m, std::string("schema version ") + std::to_string(latest_schema_version() + 5))) << m;
  EXPECT_TRUE(contains(m, std::string("version ") + std::to_string(latest_schema_version()) + " that this soiqd knows"))
      << m;
}

TEST(SqliteStoreOpen, FileThatIsNotADatabaseIsRefusedNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("notes.txt");
  {
    std::ofstream out(path);
    for (int i = 0; i < 200; ++i) out << "these are not the pages of a SQLite database\n";
  }
  auto store = SqliteStore::open(path, {});
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(store.status().message(), path)) << store.status().message();
  EXPECT_TRUE(contains(store.status().message(), "not a database")) << store.status().message();
}

TEST(SqliteStoreOpen, MissingDirectoryIsRefusedNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("no/such/dir/x.db");
  auto store = SqliteStore::open(path, {});
  ASSERT_FALSE(store.ok());
  EXPECT_TRUE(contains(store.status().message(), path)) << store.status().message();
}

TEST(SqliteStoreOpen, BadOptionsAreInvalidArgument) {
  TempDir dir;
  SqliteOptions options;
  options.read_connections = 0;
  EXPECT_EQ(SqliteStore::open(dir.file("x.db"), options).status().code(), StatusCode::kInvalidArgument);
}

TEST(SqliteStoreOpen, LockHeldByAnotherProcessPastTheTimeoutIsUnavailable) {
  TempDir dir;
  SqliteOptions options;
  options.busy_timeout_ms = 50;
  auto store = open_store(dir.file("busy.db"), options);
  // Another connection (as another process would) holds the write lock.
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(dir.file("busy.db").c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), SQLITE_OK);
  auto added = store->add_structure(new_structure("P1", "S1", "x"));
  ASSERT_FALSE(added.ok());
  EXPECT_EQ(added.status().code(), StatusCode::kUnavailable) << added.status().to_string();
  // Reads are not blocked by a writer in WAL mode.
  EXPECT_TRUE(store->counts().ok());
  sqlite3_exec(other, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(other);
  EXPECT_TRUE(store->add_structure(new_structure("P1", "S1", "x")).ok());
}

TEST(SqliteStoreOpen, KilledWriterLosesNothingAcknowledged) {
  TempDir dir;
  const std::string path = dir.file("kill.db");
  { open_store(path); }
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The child writes as fast as it can and acknowledges each id once add_structure returned.
    close(fds[0]);
    auto store = SqliteStore::open(path, {});
    if (!store.ok()) _exit(2);
    for (int i = 0;; ++i) {
      auto added = (*store)->add_structure(
          new_structure(std::string("P") + std::to_string(i % 7),
                        std::string("S") + std::to_string(i % 13) + std::string("_") + std::to_string(i % 7),
                        std::string("s") + std::to_string(i), i));
      if (!added.ok()) _exit(3);
      const int64_t id = added->structure.id;
      if (write(fds[1], &id, sizeof id) != sizeof id) _exit(4);
    }
  }
  close(fds[1]);
  std::vector<int64_t> acknowledged;
  int64_t id = 0;
  while (acknowledged.size() < 40 && read(fds[0], &id, sizeof id) == sizeof id) acknowledged.push_back(id);
  kill(child, SIGKILL);
  while (read(fds[0], &id, sizeof id) == sizeof id) acknowledged.push_back(id);
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited early with " << WEXITSTATUS(status);

  auto store = open_store(path);
  ASSERT_GE(acknowledged.size(), 40u);
  for (int64_t a : acknowledged) EXPECT_TRUE(store->get_structure(a).ok()) << "lost structure " << a;
}

}  // namespace
}  // namespace soiq::db
