#pragma once
// One libpq connection to PostgreSQL, for the PostgreSQL store: statements with parameters, every
// failure a Status by its SQLSTATE (pg_error.h), and a transaction that runs again on a
// serialization failure or a deadlock. Not thread-safe: one connection per thread at a time (the
// store keeps a pool, pg_pool.h).
//
// Parameters and results are text, except where bytes are large: a blob goes in as a binary
// parameter (pg_binary_param) and comes out of a binary result (exec_binary), so an image of
// hundreds of MB is neither hex-encoded nor parsed. A statement text run a second time on a
// connection is prepared (server-side, PQprepare) and executed by name from then on, so PostgreSQL
// parses and plans the store's statements once per connection; a text seen once costs no extra
// round trip. The cache of texts is bounded.

#include <libpq-fe.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/base/status.h"

namespace soiq::db {

// A statement's rows. Column values are text, or bytes for exec_binary's results; NULL is is_null.
class PgResult {
 public:
  explicit PgResult(PGresult* r) : r_(r, &PQclear) {}
  int rows() const { return PQntuples(r_.get()); }
  bool is_null(int row, int col) const { return PQgetisnull(r_.get(), row, col) != 0; }
  std::string text(int row, int col) const { return PQgetvalue(r_.get(), row, col); }
  int64_t int64(int row, int col) const;
  double real(int row, int col) const;
  std::optional<double> optional_real(int row, int col) const;
  // A bytea column's bytes from a text result (hex).
  std::string bytes(int row, int col) const;
  // A column's raw value (a binary result's bytes), valid as long as this result.
  std::string_view raw(int row, int col) const;
  // A column's type (PostgreSQL's type OID: 20 bigint, 23 integer, 701 double precision, …).
  unsigned type(int col) const { return PQftype(r_.get(), col); }
  int columns() const { return PQnfields(r_.get()); }
  std::string column_name(int col) const { return PQfname(r_.get(), col); }
  // The number of rows an INSERT, UPDATE or DELETE touched.
  int64_t affected() const;

 private:
  std::unique_ptr<PGresult, decltype(&PQclear)> r_;
};

// One row of a result, read by column as the record readers read a SQLite statement
// (db/sql/record_sql.h).
struct PgRow {
  const PgResult& result;
  int row;
  bool is_null(int col) const { return result.is_null(row, col); }
  std::string text(int col) const { return result.text(row, col); }
  int64_t int64(int col) const { return result.int64(row, col); }
  double real(int col) const { return result.real(row, col); }
  std::optional<double> optional_real(int col) const { return result.optional_real(row, col); }
};

// A statement parameter: text, NULL, or bytes sent as they are (pg_binary_param).
struct PgParam {
  std::optional<std::string> value;
  std::string_view bytes;  // with `binary`: the caller's bytes, not copied
  bool binary = false;
  PgParam(std::string text) : value(std::move(text)) {}                 // NOLINT: implicit, for {"a", b} lists
  PgParam(const char* text) : value(text) {}                            // NOLINT
  PgParam(std::nullopt_t) {}                                            // NOLINT
  PgParam(std::optional<std::string> text) : value(std::move(text)) {}  // NOLINT
};
// Bytes for a bytea parameter, sent in binary: they must outlive the statement's exec.
PgParam pg_binary_param(std::string_view bytes);
// Bytes as PostgreSQL's hex text for bytea (\x…), for bytea values inside an array literal.
std::string pg_bytea_hex(std::string_view bytes);
// Numbers as parameters: exactly (a double round-trips through 17 significant digits).
std::string pg_number(int64_t v);
std::string pg_number(double v);
PgParam pg_number(std::optional<double> v);  // NULL when unset

class PgConnection {
 public:
  // UNAVAILABLE (naming the server, without the password) when no connection can be made.
  static Result<PgConnection> open(const std::string& conninfo);

  // One statement with $1.. parameters; `what` names it in errors.
  Result<PgResult> exec(const std::string& sql, const std::vector<PgParam>& params, std::string_view what);
  // The same, with every result column in binary (PgResult::raw): for blobs.
  Result<PgResult> exec_binary(const std::string& sql, const std::vector<PgParam>& params, std::string_view what);
  // Statements without parameters or rows (DDL, BEGIN, COMMIT), several separated by ';'.
  Status run(const std::string& sql, std::string_view what);

  // Whether the connection is up; reset() reconnects with the same parameters (after the server
  // restarted or the network dropped it) and says whether that worked.
  bool healthy() const;
  bool reset();

 private:
  explicit PgConnection(PGconn* c) : c_(c, &PQfinish) {}
  Status failure(PGresult* r, std::string_view what) const;
  Result<PgResult> execute(const std::string& sql, const std::vector<PgParam>& params, std::string_view what,
                           int result_format);
  // The name of `sql` prepared on this connection; "" to run it unprepared.
  Result<std::string> prepared(const std::string& sql, int param_count, std::string_view what);

  std::unique_ptr<PGconn, decltype(&PQfinish)> c_;
  std::unordered_map<std::string, std::string> prepared_;  // text -> server-side name ("" seen once)
  int64_t prepared_count_ = 0;
};

// How a transaction sees other transactions: READ COMMITTED; one snapshot for all its reads and
// no writes (REPEATABLE READ, READ ONLY: a page and its counts agree); or SERIALIZABLE, for writes
// that read before they write, where two replicas could otherwise interleave.
enum class PgIsolation { kReadCommitted, kSnapshotReadOnly, kSerializable };

// Runs `body` in one transaction and commits it; on a serialization failure or deadlock rolls back
// and runs it again, up to `attempts` times in all, after a short random wait that doubles each
// time (up to 50 ms). Any other failure rolls back and is returned.
Status pg_transaction(PgConnection& c, const std::function<Status()>& body,
                      PgIsolation isolation = PgIsolation::kReadCommitted, int attempts = 5);

}  // namespace soiq::db
