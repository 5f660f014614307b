// The PostgreSQL store's connection pool on a real PostgreSQL 15: it migrates the schema at open,
// bounds the connections a replica holds, and many threads through few connections run
// serializable transactions that conflict, retried until every one has committed.
#include "db/postgres/pg_pool.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "db/postgres/pg_schema.h"
#include "tests/db/pg_database.h"

namespace soiq::db {
namespace {

using namespace std::chrono_literals;

TEST_F(PgTest, APoolOpensItsConnectionsAndMigrates) {
  auto pool = PgPool::open(conninfo(), 3);
  ASSERT_TRUE(pool.ok()) << pool.status().to_string();
  EXPECT_EQ((*pool)->size(), 3);
  auto lease = (*pool)->acquire(1s);
  ASSERT_TRUE(lease.ok());
  EXPECT_EQ(*pg_schema_version(**lease), pg_latest_schema_version());
}

TEST_F(PgTest, ABadPoolSizeOrAddressFailsAtOpen) {
  EXPECT_EQ(PgPool::open(conninfo(), 0).status().code(), StatusCode::kInvalidArgument);
  const int port = soiq::testing::free_loopback_port();
  auto pool = PgPool::open("host=127.0.0.1 port=" + std::to_string(port) + " user=soiq dbname=x connect_timeout=2", 2);
  EXPECT_EQ(pool.status().code(), StatusCode::kUnavailable);
}

TEST_F(PgTest, ALeaseWaitsForAFreeConnectionAndTimesOutNamingThePool) {
  auto pool = PgPool::open(conninfo(), 2);
  ASSERT_TRUE(pool.ok());
  auto a = (*pool)->acquire(1s);
  auto b = (*pool)->acquire(1s);
  ASSERT_TRUE(a.ok() && b.ok());
  auto c = (*pool)->acquire(50ms);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kDeadlineExceeded);
  EXPECT_EQ(c.status().message(), "all 2 PostgreSQL connections stayed busy for 50 ms");
  // A lease given back in another thread wakes the waiting one.
  std::thread giver([lease = std::move(*a)]() mutable { std::this_thread::sleep_for(20ms); });
  auto d = (*pool)->acquire(5s);
  giver.join();
  EXPECT_TRUE(d.ok());
}

TEST_F(PgTest, ConflictingSerializableTransactionsAreRetriedUntilEachCommits) {
  auto pool = PgPool::open(conninfo(), 3);
  ASSERT_TRUE(pool.ok());
  {
    auto lease = (*pool)->acquire(1s);
    ASSERT_TRUE(lease.ok());
    ASSERT_TRUE(
        (*lease)->run("CREATE TABLE counter (n bigint NOT NULL); INSERT INTO counter VALUES (0)", "setup").ok());
  }
  constexpr int kThreads = 6, kEach = 20;
  std::vector<std::thread> threads;
  std::atomic<int> failed{0};
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < kEach; ++i) {
        auto lease = (*pool)->acquire(30s);
        if (!lease.ok()) {
          ++failed;
          continue;
        }
        PgConnection& c = **lease;
        // Read, then write what was read plus one: two of these at once cannot both commit
        // under SERIALIZABLE (SQLSTATE 40001), so pg_transaction runs the loser again.
        const Status s = pg_transaction(
            c,
            [&]() -> Status {
              SOIQ_ASSIGN_OR_RETURN(PgResult r, c.exec("SELECT n FROM counter", {}, "read the counter"));
              return c.exec("UPDATE counter SET n = $1", {std::to_string(r.int64(0, 0) + 1)}, "write the counter")
                  .status();
            },
            PgIsolation::kSerializable, /*attempts=*/200);
        if (!s.ok()) ++failed;
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(failed.load(), 0);
  auto lease = (*pool)->acquire(1s);
  ASSERT_TRUE(lease.ok());
  EXPECT_EQ((*lease)->exec("SELECT n FROM counter", {}, "read")->int64(0, 0), kThreads * kEach);
}

}  // namespace
}  // namespace soiq::db
