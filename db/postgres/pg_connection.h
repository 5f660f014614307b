#pragma once
// One libpq connection to PostgreSQL, for the PostgreSQL store: statements with parameters and
// results as text (bytea as PostgreSQL's hex text, decoded by `bytes`), every failure a Status by
// its SQLSTATE (pg_error.h), and a transaction that runs again on a serialization failure or a
// deadlock. Not thread-safe: one connection per thread at a time (the store keeps a pool).

#include <libpq-fe.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::db {

// A statement's rows. Column values are text; NULL is is_null.
class PgResult {
 public:
  explicit PgResult(PGresult* r) : r_(r, &PQclear) {}
  int rows() const { return PQntuples(r_.get()); }
  bool is_null(int row, int col) const { return PQgetisnull(r_.get(), row, col) != 0; }
  std::string text(int row, int col) const { return PQgetvalue(r_.get(), row, col); }
  int64_t int64(int row, int col) const;
  double real(int row, int col) const;
  // A bytea column's bytes.
  std::string bytes(int row, int col) const;

 private:
  std::unique_ptr<PGresult, decltype(&PQclear)> r_;
};

// A statement parameter: text, or NULL. Bytes for a bytea go through pg_bytea_param.
using PgParam = std::optional<std::string>;
PgParam pg_bytea_param(std::string_view bytes);

class PgConnection {
 public:
  // UNAVAILABLE (naming the server, without the password) when no connection can be made.
  static Result<PgConnection> open(const std::string& conninfo);

  // One statement with $1.. parameters; `what` names it in errors.
  Result<PgResult> exec(const std::string& sql, const std::vector<PgParam>& params, std::string_view what);
  // Statements without parameters or rows (DDL, BEGIN, COMMIT), several separated by ';'.
  Status run(const std::string& sql, std::string_view what);

  // Whether the connection is up; reset() reconnects with the same parameters (after the server
  // restarted or the network dropped it) and says whether that worked.
  bool healthy() const;
  bool reset();

 private:
  explicit PgConnection(PGconn* c) : c_(c, &PQfinish) {}
  Status failure(PGresult* r, std::string_view what) const;

  std::unique_ptr<PGconn, decltype(&PQfinish)> c_;
};

// Runs `body` in one transaction (READ COMMITTED unless `serializable`) and commits it; on a
// serialization failure or deadlock rolls back and runs it again, up to `attempts` times in all,
// after a short random wait that doubles each time (up to 50 ms). Any other failure rolls back and is returned.
Status pg_transaction(PgConnection& c, const std::function<Status()>& body, bool serializable = false,
                      int attempts = 5);

}  // namespace soiq::db
