// The PostgreSQL server the PostgreSQL store's tests run on: a real postgres, started in a
// temporary folder on a free loopback port, that answers SQL over libpq and is gone after stop.
#include "tests/support/postgres_process.h"

#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <memory>
#include <string>

namespace soiq::testing {
namespace {

using Connection = std::unique_ptr<PGconn, decltype(&PQfinish)>;
using Result = std::unique_ptr<PGresult, decltype(&PQclear)>;

Result exec(PGconn* c, const char* sql) { return Result(PQexec(c, sql), &PQclear); }

TEST(PostgresProcess, StartsAnswersSqlAndStops) {
  PostgresProcess pg;
  const std::string why = pg.start();
  ASSERT_EQ(why, "");
  ASSERT_GT(pg.port(), 0);
  {
    Connection c(PQconnectdb(pg.conninfo("postgres").c_str()), &PQfinish);
    ASSERT_EQ(PQstatus(c.get()), CONNECTION_OK) << PQerrorMessage(c.get());
    Result version = exec(c.get(), "SELECT current_setting('server_version_num')::int");
    ASSERT_EQ(PQresultStatus(version.get()), PGRES_TUPLES_OK) << PQerrorMessage(c.get());
    EXPECT_GE(std::stoi(PQgetvalue(version.get(), 0, 0)), 150000);  // PostgreSQL 15 or newer
    ASSERT_EQ(PQresultStatus(exec(c.get(), "CREATE TABLE t (id bigint PRIMARY KEY, v bytea)").get()), PGRES_COMMAND_OK);
    ASSERT_EQ(PQresultStatus(exec(c.get(), "INSERT INTO t VALUES (7, '\\x00ff'::bytea)").get()), PGRES_COMMAND_OK);
    Result row = exec(c.get(), "SELECT id, length(v) FROM t");
    ASSERT_EQ(PQntuples(row.get()), 1);
    EXPECT_EQ(std::string(PQgetvalue(row.get(), 0, 0)), "7");
    EXPECT_EQ(std::string(PQgetvalue(row.get(), 0, 1)), "2");
  }
  const std::string conninfo = pg.conninfo("postgres");
  pg.stop();
  EXPECT_EQ(PQping(conninfo.c_str()), PQPING_NO_RESPONSE);
}

}  // namespace
}  // namespace soiq::testing
