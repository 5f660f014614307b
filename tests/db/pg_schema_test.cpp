// The PostgreSQL store's connection and schema on a real PostgreSQL 15 (tests/support/
// postgres_process.h): SQLSTATEs become the right Status, a transaction runs again after a
// serialization failure, the schema is the SQLite store's table for table and column for column,
// and replicas starting together migrate once.
#include "db/postgres/pg_schema.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "db/postgres/pg_connection.h"
#include "db/postgres/pg_error.h"
#include "tests/db/pg_database.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;

TEST(PgStatus, SqlStatesMapToTheirCodes) {
  EXPECT_EQ(pg_status("40001", "could not serialize", "x").code(), StatusCode::kAborted);
  EXPECT_EQ(pg_status("40P01", "deadlock detected", "x").code(), StatusCode::kAborted);
  EXPECT_EQ(pg_status("08006", "connection failure", "x").code(), StatusCode::kUnavailable);
  EXPECT_EQ(pg_status("57P01", "terminating connection", "x").code(), StatusCode::kUnavailable);
  EXPECT_EQ(pg_status("23505", "duplicate key", "x").code(), StatusCode::kAlreadyExists);
  EXPECT_EQ(pg_status("23503", "foreign key", "x").code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(pg_status("53100", "disk full", "x").code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(pg_status("28P01", "password", "x").code(), StatusCode::kUnauthenticated);
  EXPECT_EQ(pg_status("42501", "permission", "x").code(), StatusCode::kPermissionDenied);
  EXPECT_EQ(pg_status("XX001", "data corrupted", "x").code(), StatusCode::kDataLoss);
  EXPECT_EQ(pg_status("42601", "syntax error", "x").code(), StatusCode::kInternal);
  const Status s = pg_status("23505", "duplicate key value\n", "add a patient");
  EXPECT_EQ(s.message(), "add a patient: duplicate key value (SQLSTATE 23505)");
  EXPECT_TRUE(pg_retryable(pg_status("40001", "", "x")));
  EXPECT_FALSE(pg_retryable(pg_status("23505", "", "x")));
}

TEST(PgConnectionOpen, AServerNobodyRunsIsUnavailableNamingIt) {
  const int port = soiq::testing::free_loopback_port();
  auto c = PgConnection::open("host=127.0.0.1 port=" + std::to_string(port) + " user=soiq dbname=x connect_timeout=2");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kUnavailable);
  EXPECT_TRUE(contains(c.status().message(), "127.0.0.1:" + std::to_string(port) + "/x")) << c.status().message();
}

TEST_F(PgTest, StatementsTakeParametersAndFailWithTheirSqlState) {
  auto c = connect();
  ASSERT_TRUE(c.ok());
  ASSERT_TRUE(c->run("CREATE TABLE t (id bigint PRIMARY KEY, name text, b bytea)", "create t").ok());
  const std::string bytes("\0\x01\xff zero", 8);
  ASSERT_TRUE(c->exec("INSERT INTO t VALUES ($1, $2, $3)", {"1", std::nullopt, pg_binary_param(bytes)}, "insert").ok());
  auto row = c->exec("SELECT id, name, b FROM t WHERE id = $1", {"1"}, "select");
  ASSERT_TRUE(row.ok());
  ASSERT_EQ(row->rows(), 1);
  EXPECT_EQ(row->int64(0, 0), 1);
  EXPECT_TRUE(row->is_null(0, 1));
  EXPECT_EQ(row->bytes(0, 2), bytes);
  const auto again = c->exec("INSERT INTO t VALUES ($1, 'x', NULL)", {"1"}, "insert patient 1 again");
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.status().code(), StatusCode::kAlreadyExists);
  EXPECT_TRUE(contains(again.status().message(), "insert patient 1 again: ")) << again.status().message();
  EXPECT_TRUE(contains(again.status().message(), "SQLSTATE 23505")) << again.status().message();
  // Text that is not UTF-8 is the input's fault, said as such (SQLite would have stored it).
  const auto latin1 = c->exec("INSERT INTO t VALUES (2, $1, NULL)", {std::string("M\xfcller")}, "insert a name");
  EXPECT_EQ(latin1.status().code(), StatusCode::kInvalidArgument) << latin1.status().to_string();
}

TEST_F(PgTest, ATransactionRunsAgainAfterASerializationFailureAndRollsBackOtherFailures) {
  auto c = connect();
  ASSERT_TRUE(c.ok());
  ASSERT_TRUE(c->run("CREATE TABLE t (id bigint PRIMARY KEY)", "create t").ok());
  int runs = 0;
  const Status s = pg_transaction(*c, [&]() -> Status {
    ++runs;
    SOIQ_RETURN_IF_ERROR(c->exec("INSERT INTO t VALUES ($1)", {std::to_string(runs)}, "insert").status());
    if (runs < 3) return Status(StatusCode::kAborted, "could not serialize access (SQLSTATE 40001)");
    return ok_status();
  });
  ASSERT_TRUE(s.ok()) << s.to_string();
  EXPECT_EQ(runs, 3);
  auto rows = c->exec("SELECT id FROM t", {}, "select");
  ASSERT_TRUE(rows.ok());
  ASSERT_EQ(rows->rows(), 1);  // the first two attempts were rolled back
  EXPECT_EQ(rows->int64(0, 0), 3);

  const Status other = pg_transaction(*c, [&]() -> Status {
    SOIQ_RETURN_IF_ERROR(c->exec("INSERT INTO t VALUES (4)", {}, "insert").status());
    return failed_precondition("no");
  });
  EXPECT_EQ(other.code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(c->exec("SELECT id FROM t", {}, "select")->rows(), 1);
}

// Table names and each table's column names, in PostgreSQL and in a fresh SQLite store.
std::map<std::string, std::set<std::string>> pg_columns(PgConnection& c) {
  std::map<std::string, std::set<std::string>> out;
  auto r = c.exec(
      "SELECT table_name, column_name FROM information_schema.columns WHERE table_schema = 'public' "
      "AND table_name <> 'soiq_schema'",
      {}, "list columns");
  EXPECT_TRUE(r.ok());
  if (!r.ok()) return out;
  for (int i = 0; i < r->rows(); ++i) out[r->text(i, 0)].insert(r->text(i, 1));
  return out;
}

std::map<std::string, std::set<std::string>> sqlite_columns() {
  testing::TempDir dir;
  const std::string path = dir.file("schema.db");
  { auto store = testing::open_store(path); }
  std::map<std::string, std::set<std::string>> out;
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db,
                     "SELECT m.name, p.name FROM sqlite_master m JOIN pragma_table_info(m.name) p "
                     "WHERE m.type = 'table' AND m.name NOT LIKE 'sqlite_%'",
                     -1, &st, nullptr);
  while (sqlite3_step(st) == SQLITE_ROW) {
    out[reinterpret_cast<const char*>(sqlite3_column_text(st, 0))].insert(
        reinterpret_cast<const char*>(sqlite3_column_text(st, 1)));
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  return out;
}

TEST_F(PgTest, TheSchemaIsTheSqliteStoresTableForTableAndColumnForColumn) {
  auto c = connect();
  ASSERT_TRUE(c.ok());
  ASSERT_TRUE(pg_migrate(*c).ok());
  EXPECT_EQ(*pg_schema_version(*c), pg_latest_schema_version());
  const auto pg = pg_columns(*c);
  const auto lite = sqlite_columns();
  ASSERT_FALSE(lite.empty());
  EXPECT_EQ(pg, lite);
  ASSERT_TRUE(pg_migrate(*c).ok());  // again: nothing to do
  EXPECT_EQ(c->exec("SELECT count(*) FROM soiq_schema", {}, "count")->int64(0, 0), 1);
}

TEST_F(PgTest, EveryTextColumnComparesInByteOrderWhateverTheDatabasesLocale) {
  auto c = connect();
  ASSERT_TRUE(c.ok());
  ASSERT_TRUE(pg_migrate(*c).ok());
  auto r = c->exec(
      "SELECT table_name || '.' || column_name, coalesce(collation_name, '') FROM information_schema.columns "
      "WHERE table_schema = 'public' AND data_type = 'text' AND table_name <> 'soiq_schema'",
      {}, "list text columns");
  ASSERT_TRUE(r.ok());
  ASSERT_GT(r->rows(), 20);
  for (int i = 0; i < r->rows(); ++i) EXPECT_EQ(r->text(i, 1), "C") << r->text(i, 0);
  // So does lower() of them, which changes ASCII letters only (as SQLite's does).
  auto lower = c->exec("SELECT lower(name) FROM (SELECT $1::text COLLATE \"C\" AS name) n", {"\u00c9A"}, "lower");
  ASSERT_TRUE(lower.ok()) << lower.status().to_string();
  EXPECT_EQ(lower->text(0, 0), "\u00c9a");
}

TEST_F(PgTest, ReplicasStartingTogetherMigrateOnce) {
  std::vector<std::thread> replicas;
  std::vector<Status> results(4);
  for (size_t i = 0; i < results.size(); ++i) {
    replicas.emplace_back([&, i] {
      auto c = connect();
      results[i] = c.ok() ? pg_migrate(*c) : c.status();
    });
  }
  for (std::thread& t : replicas) t.join();
  for (const Status& s : results) EXPECT_TRUE(s.ok()) << s.to_string();
  auto c = connect();
  ASSERT_TRUE(c.ok());
  auto versions = c->exec("SELECT version FROM soiq_schema", {}, "read");
  ASSERT_TRUE(versions.ok());
  ASSERT_EQ(versions->rows(), 1);
  EXPECT_EQ(versions->int64(0, 0), pg_latest_schema_version());
}

TEST_F(PgTest, ADatabaseOfANewerSoiqdIsFailedPrecondition) {
  auto c = connect();
  ASSERT_TRUE(c.ok());
  ASSERT_TRUE(pg_migrate(*c).ok());
  ASSERT_TRUE(c->run("UPDATE soiq_schema SET version = 99", "pretend a newer soiqd").ok());
  const Status s = pg_migrate(*c);
  EXPECT_EQ(s.code(), StatusCode::kFailedPrecondition);
  EXPECT_TRUE(contains(s.message(), "schema version 99, newer than version " +
                                        std::to_string(pg_latest_schema_version()) + " that this soiqd knows"))
      << s.message();
}

}  // namespace
}  // namespace soiq::db
