#include "db/postgres/pg_connection.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <thread>

#include "db/postgres/pg_error.h"

namespace soiq::db {

int64_t PgResult::int64(int row, int col) const { return std::strtoll(PQgetvalue(r_.get(), row, col), nullptr, 10); }

double PgResult::real(int row, int col) const { return std::strtod(PQgetvalue(r_.get(), row, col), nullptr); }

std::optional<double> PgResult::optional_real(int row, int col) const {
  if (is_null(row, col)) return std::nullopt;
  return real(row, col);
}

std::string PgResult::bytes(int row, int col) const {
  size_t n = 0;
  unsigned char* raw = PQunescapeBytea(reinterpret_cast<const unsigned char*>(PQgetvalue(r_.get(), row, col)), &n);
  if (raw == nullptr) return {};
  std::string out(reinterpret_cast<const char*>(raw), n);
  PQfreemem(raw);
  return out;
}

std::string_view PgResult::raw(int row, int col) const {
  return {PQgetvalue(r_.get(), row, col), size_t(PQgetlength(r_.get(), row, col))};
}

int64_t PgResult::affected() const { return std::strtoll(PQcmdTuples(r_.get()), nullptr, 10); }

PgParam pg_binary_param(std::string_view bytes) {
  PgParam p(std::nullopt);
  p.bytes = bytes;
  p.binary = true;
  return p;
}

std::string pg_bytea_hex(std::string_view bytes) {
  // PostgreSQL's hex format for bytea input: \x then two hex digits per byte.
  static constexpr char kHex[] = "0123456789abcdef";
  std::string text = "\\x";
  text.reserve(2 + 2 * bytes.size());
  for (const unsigned char b : bytes) text += kHex[b >> 4], text += kHex[b & 15];
  return text;
}

std::string pg_number(int64_t v) { return std::to_string(v); }

std::string pg_number(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;  // shortest text that reads back exactly
  return std::string(buffer, end);
}

PgParam pg_number(std::optional<double> v) { return v ? PgParam(pg_number(*v)) : PgParam(std::nullopt); }

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

namespace {

// Past this many distinct statement texts a connection runs new ones unprepared: the store's
// statements are a few dozen texts, and its filtered queries some hundreds at most.
constexpr size_t kMaxPrepared = 512;

}  // namespace

Result<std::string> PgConnection::prepared(const std::string& sql, int param_count, std::string_view what) {
  // The first time a text is seen it runs unprepared (preparing costs a round trip of its own, lost
  // on a statement that never comes back); the second time it is prepared, for good.
  auto it = prepared_.find(sql);
  if (it == prepared_.end()) {
    if (prepared_.size() < kMaxPrepared) prepared_.emplace(sql, std::string());
    return std::string();
  }
  if (!it->second.empty()) return it->second;
  std::string name = "soiq" + std::to_string(++prepared_count_);
  PGresult* r = PQprepare(c_.get(), name.c_str(), sql.c_str(), param_count, nullptr);
  const bool ok = r != nullptr && PQresultStatus(r) == PGRES_COMMAND_OK;
  if (!ok) {
    const Status status = failure(r, what);
    PQclear(r);
    return status;
  }
  PQclear(r);
  it->second = name;
  return name;
}

Result<PgResult> PgConnection::execute(const std::string& sql, const std::vector<PgParam>& params,
                                       std::string_view what, int result_format) {
  std::vector<const char*> values;
  std::vector<int> lengths, formats;
  values.reserve(params.size());
  for (const PgParam& p : params) {
    if (p.binary) {
      // PostgreSQL's own bound on a bytea value; larger is refused here, before anything is sent.
      if (p.bytes.size() >= (size_t{1} << 30)) {
        return Status(StatusCode::kResourceExhausted, std::string(what) + ": " + std::to_string(p.bytes.size()) +
                                                          " bytes; PostgreSQL stores at most 1 GiB in one value");
      }
      values.push_back(p.bytes.empty() ? "" : p.bytes.data());  // a null pointer would be SQL NULL
      lengths.push_back(int(p.bytes.size()));
    } else {
      values.push_back(p.value ? p.value->data() : nullptr);
      lengths.push_back(p.value ? int(p.value->size()) : 0);
    }
    formats.push_back(p.binary ? 1 : 0);
  }
  SOIQ_ASSIGN_OR_RETURN(const std::string name, prepared(sql, int(params.size()), what));
  PGresult* r = name.empty() ? PQexecParams(c_.get(), sql.c_str(), int(values.size()), nullptr, values.data(),
                                            lengths.data(), formats.data(), result_format)
                             : PQexecPrepared(c_.get(), name.c_str(), int(values.size()), values.data(), lengths.data(),
                                              formats.data(), result_format);
  const ExecStatusType s = r != nullptr ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (s != PGRES_TUPLES_OK && s != PGRES_COMMAND_OK) {
    const Status status = failure(r, what);
    PQclear(r);
    return status;
  }
  return PgResult(r);
}

Result<PgResult> PgConnection::exec(const std::string& sql, const std::vector<PgParam>& params, std::string_view what) {
  return execute(sql, params, what, 0);
}

Result<PgResult> PgConnection::exec_binary(const std::string& sql, const std::vector<PgParam>& params,
                                           std::string_view what) {
  return execute(sql, params, what, 1);
}

bool PgConnection::healthy() const { return PQstatus(c_.get()) == CONNECTION_OK; }

bool PgConnection::reset() {
  PQreset(c_.get());
  prepared_.clear();  // a new session: the server forgot them
  prepared_count_ = 0;
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

namespace {

const char* begin_sql(PgIsolation isolation) {
  switch (isolation) {
    case PgIsolation::kReadCommitted:
      return "BEGIN";
    case PgIsolation::kSnapshotReadOnly:
      return "BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY";
    case PgIsolation::kSerializable:
      return "BEGIN ISOLATION LEVEL SERIALIZABLE";
  }
  return "BEGIN";
}

}  // namespace

Status pg_transaction(PgConnection& c, const std::function<Status()>& body, PgIsolation isolation, int attempts) {
  thread_local std::mt19937 rng(std::random_device{}());
  std::chrono::microseconds wait(500);
  Status last = ok_status();
  for (int attempt = 0; attempt < std::max(1, attempts); ++attempt) {
    if (attempt > 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int64_t>(
          wait.count() / 2, wait.count())(rng)));                   // jitter: concurrent retries do not collide again
      wait = std::min(wait * 2, std::chrono::microseconds(50000));  // at most 50 ms apart
    }
    SOIQ_RETURN_IF_ERROR(c.run(begin_sql(isolation), "begin a transaction"));
    last = body();
    if (last.ok()) last = c.run("COMMIT", "commit");
    if (last.ok()) return last;
    (void)c.run("ROLLBACK", "roll back");
    if (!pg_retryable(last)) return last;
  }
  return last;
}

}  // namespace soiq::db
