// Many threads on one store, as the server's worker pool calls it: SQLite, and PostgreSQL, whose
// serializable writers conflict (40001) when they overlap, most on a fresh database whose tiny
// tables are scanned whole: every write must still succeed, with nothing lost.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>

#include "db/sqlite/sqlite_store.h"
#include "tests/db/store_backends.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::new_structure;
using testing::open_store;
using testing::TempDir;

void eight_threads_writing_and_reading(Store* store) {
  ASSERT_NE(store, nullptr);
  constexpr int kThreads = 8, kPerThread = 40;
  std::atomic<int> errors{0};
  std::vector<std::vector<int64_t>> ids(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const auto fail = [&](const Status& s) {
        ADD_FAILURE() << "thread " << t << ": " << s.to_string();
        ++errors;
      };
      for (int i = 0; i < kPerThread; ++i) {
        // Threads share patients, studies and surfaces, so upserts and dedup race each other.
        const std::string patient = std::string("P") + std::to_string(i % 5);
        auto added = store->add_structure(new_structure(patient, std::string("S") + std::to_string(i % 5),
                                                        std::string("s") + std::to_string(t), double(i % 10)));
        if (!added.ok()) {
          fail(added.status());
          continue;
        }
        ids[t].push_back(added->structure.id);
        auto back = store->get_structure(added->structure.id);
        if (!back.ok()) fail(back.status());
        Stage1Filter f;
        f.patient_id_glob = patient;
        auto found = store->stage1(f, 1'000'000);
        if (!found.ok()) fail(found.status());
        auto page = store->list_structures(StructureFilter{patient, "", "", ""}, PageRequest{});
        if (!page.ok()) fail(page.status());
        if (i % 10 == 0) {
          auto n = store->counts();
          if (!n.ok()) fail(n.status());
        }
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(errors.load(), 0);
  std::set<int64_t> all;
  for (const auto& v : ids) all.insert(v.begin(), v.end());
  EXPECT_EQ(all.size(), size_t(kThreads * kPerThread));
  auto n = store->counts();
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n->structures, kThreads * kPerThread);
  EXPECT_EQ(n->surfaces, 10);
  EXPECT_EQ(n->patients, 5);
  EXPECT_EQ(n->studies, 5);
  auto everything = store->stage1(Stage1Filter{}, 1'000'000);
  ASSERT_TRUE(everything.ok());
  EXPECT_EQ(everything->size(), size_t(kThreads * kPerThread));
}

TEST(SqliteStoreConcurrency, EightThreadsWritingAndReadingLoseNothing) {
  TempDir dir;
  SqliteOptions options;
  options.read_connections = 3;  // fewer readers than threads: some wait for a connection
  auto store = open_store(dir.file("threads.db"), options);
  eight_threads_writing_and_reading(store.get());
}

TEST(PgStoreConcurrency, EightThreadsWritingAndReadingLoseNothing) {
  TempDir dir;
  auto store = testing::PostgresBackend::open(dir);  // 4 connections: some threads wait for one
  eight_threads_writing_and_reading(store.get());
}

}  // namespace
}  // namespace soiq::db
