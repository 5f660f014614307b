#pragma once
// The store's SQL session (db/sql/sql_session.h) on one PostgreSQL connection, inside the
// transaction PgStore opened on it. A statement's ?n parameters become $n; parameters go as text
// (numbers exactly, pg_number) and blobs in binary; results come back in binary, so numbers are
// read without parsing text and doubles exactly, and a blob is its bytes.

#include <string>
#include <string_view>
#include <vector>

#include "db/postgres/pg_connection.h"
#include "db/sql/sql_session.h"

namespace soiq::db {

class PgSession : public SqlSession {
 public:
  explicit PgSession(PgConnection& c) : c_(c) {}
  SqlDialect dialect() const override { return SqlDialect::kPostgres; }
  Result<SqlStatement> prepare(std::string_view sql) override;
  PgConnection& connection() { return c_; }

 private:
  PgConnection& c_;
};

// `sql` with SQLite's numbered parameters ?n written as PostgreSQL's $m, numbered again without
// gaps: PostgreSQL must know the type of every $m up to the highest, and cannot for one the text
// never uses (SQLite leaves it NULL), so `numbers[n]` is n's new number, 0 for one not in the text.
// The store's SQL has no '?' in a literal or identifier.
struct PgNumberedSql {
  std::string sql;
  std::vector<int> numbers;
};
PgNumberedSql pg_numbered_parameters(std::string_view sql);

}  // namespace soiq::db
