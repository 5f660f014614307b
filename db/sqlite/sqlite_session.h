#pragma once
// The store's SQL session (db/sql/sql_session.h) on one SQLite connection, inside the transaction
// SqliteStore opened on it: statements come from the connection's cache of prepared statements.

#include "db/sql/sql_session.h"
#include "db/sqlite/sqlite_connection.h"

namespace soiq::db {

class SqliteSession : public SqlSession {
 public:
  explicit SqliteSession(Connection& c) : c_(c) {}
  SqlDialect dialect() const override { return SqlDialect::kSqlite; }
  Result<SqlStatement> prepare(std::string_view sql) override;

 private:
  Connection& c_;
};

}  // namespace soiq::db
