#include "db/postgres/pg_connection.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <random>
#include <thread>

#include "db/postgres/pg_error.h"

namespace soiq::db {

int64_t PgResult::int64(int row, int col) const { return std::strtoll(PQgetvalue(r_.get(), row, col), nullptr, 10); }

double PgResult::real(int row, int col) const { return std::strtod(PQgetvalue(r_.get(), row, col), nullptr); }

std::string PgResult::bytes(int row, int col) const {
  size_t n = 0;
  unsigned char* raw = PQunescapeBytea(reinterpret_cast<const unsigned char*>(PQgetvalue(r_.get(), row, col)), &n);
  if (raw == nullptr) return {};
  std::string out(reinterpret_cast<const char*>(raw), n);
  PQfreemem(raw);
  return out;
}

PgParam pg_bytea_param(std::string_view bytes) {
  // PostgreSQL's hex format for bytea input: \x then two hex digits per byte.
  static constexpr char kHex[] = "0123456789abcdef";
  std::string text = "\\x";
  text.reserve(2 + 2 * bytes.size());
  for (const unsigned char b : bytes) text += kHex[b >> 4], text += kHex[b & 15];
  return text;
}

Result<PgConnection> PgConnection::open(const std::string& conninfo) {
  PGconn* c = PQconnectdb(conninfo.c_str());
  if (c == nullptr) return Status(StatusCode::kUnavailable, "cannot connect to PostgreSQL: out of memory");
  PgConnection connection(c);
  if (PQstatus(c) != CONNECTION_OK) {
    const char* host = PQhost(c);
    const char* port = PQport(c);
    const char* db = PQdb(c);
    return pg_status("08001", PQerrorMessage(c),
                     std::string("cannot connect to PostgreSQL at ") + (host ? host : "?") + ":" + (port ? port : "?") +
                         "/" + (db ? db : "?"));
  }
  return connection;
}

Status PgConnection::failure(PGresult* r, std::string_view what) const {
  const char* state = r != nullptr ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  const char* message = r != nullptr ? PQresultErrorMessage(r) : "";
  if (message == nullptr || *message == '\0') message = PQerrorMessage(c_.get());
  return pg_status(state ? state : "", message, what);
}

Result<PgResult> PgConnection::exec(const std::string& sql, const std::vector<PgParam>& params, std::string_view what) {
  std::vector<const char*> values;
  values.reserve(params.size());
  for (const PgParam& p : params) values.push_back(p ? p->c_str() : nullptr);
  PGresult* r = PQexecParams(c_.get(), sql.c_str(), int(values.size()), nullptr, values.data(), nullptr, nullptr, 0);
  const ExecStatusType s = r != nullptr ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (s != PGRES_TUPLES_OK && s != PGRES_COMMAND_OK) {
    const Status status = failure(r, what);
    PQclear(r);
    return status;
  }
  return PgResult(r);
}

bool PgConnection::healthy() const { return PQstatus(c_.get()) == CONNECTION_OK; }

bool PgConnection::reset() {
  PQreset(c_.get());
  return healthy();
}

Status PgConnection::run(const std::string& sql, std::string_view what) {
  PGresult* r = PQexec(c_.get(), sql.c_str());
  const ExecStatusType s = r != nullptr ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  const Status status =
      (s == PGRES_COMMAND_OK || s == PGRES_TUPLES_OK || s == PGRES_EMPTY_QUERY) ? ok_status() : failure(r, what);
  PQclear(r);
  return status;
}

Status pg_transaction(PgConnection& c, const std::function<Status()>& body, bool serializable, int attempts) {
  thread_local std::mt19937 rng(std::random_device{}());
  std::chrono::microseconds wait(500);
  Status last = ok_status();
  for (int attempt = 0; attempt < std::max(1, attempts); ++attempt) {
    if (attempt > 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int64_t>(
          wait.count() / 2, wait.count())(rng)));                   // jitter: concurrent retries do not collide again
      wait = std::min(wait * 2, std::chrono::microseconds(50000));  // at most 50 ms apart
    }
    SOIQ_RETURN_IF_ERROR(c.run(serializable ? "BEGIN ISOLATION LEVEL SERIALIZABLE" : "BEGIN", "begin a transaction"));
    last = body();
    if (last.ok()) last = c.run("COMMIT", "commit");
    if (last.ok()) return last;
    (void)c.run("ROLLBACK", "roll back");
    if (!pg_retryable(last)) return last;
  }
  return last;
}

}  // namespace soiq::db
