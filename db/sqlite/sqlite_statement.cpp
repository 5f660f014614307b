#include "db/sqlite/sqlite_statement.h"

#include <sqlite3.h>

#include <utility>

#include "db/sqlite/sqlite_error.h"

namespace soiq::db {

Statement::Statement(sqlite3* db, sqlite3_stmt* stmt, bool owned, bool* in_use)
    : db_(db), stmt_(stmt), owned_(owned), in_use_(in_use) {}

Statement::~Statement() {
  if (stmt_ == nullptr) return;
  if (owned_) {
    sqlite3_finalize(stmt_);
    return;
  }
  // Reset so a read statement releases its snapshot, and clear so no stale value leaks into the
  // next use that forgets a parameter.
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
  if (in_use_ != nullptr) *in_use_ = false;
}

Statement::Statement(Statement&& other) noexcept
    : db_(other.db_),
      stmt_(std::exchange(other.stmt_, nullptr)),
      owned_(other.owned_),
      in_use_(std::exchange(other.in_use_, nullptr)),
      bind_rc_(other.bind_rc_),
      bind_index_(other.bind_index_) {}

void Statement::note_bind(int rc, int i) {
  if (rc != SQLITE_OK && bind_rc_ == SQLITE_OK) {
    bind_rc_ = rc;
    bind_index_ = i;
  }
}

void Statement::bind(int i, int64_t v) { note_bind(sqlite3_bind_int64(stmt_, i, v), i); }
void Statement::bind(int i, double v) { note_bind(sqlite3_bind_double(stmt_, i, v), i); }
void Statement::bind(int i, std::optional<double> v) {
  note_bind(v ? sqlite3_bind_double(stmt_, i, *v) : sqlite3_bind_null(stmt_, i), i);
}
void Statement::bind(int i, std::string_view text) {
  note_bind(sqlite3_bind_text64(stmt_, i, text.data(), text.size(), SQLITE_TRANSIENT, SQLITE_UTF8), i);
}
void Statement::bind_blob(int i, const void* data, size_t size) {
  // A zero-length blob must still be a blob, not NULL: sqlite3_bind_blob64 with a null pointer binds
  // NULL, so point at a static byte.
  static const char kEmpty = 0;
  note_bind(sqlite3_bind_blob64(stmt_, i, size == 0 ? &kEmpty : data, size, SQLITE_TRANSIENT), i);
}

Result<bool> Statement::step() {
  if (bind_rc_ != SQLITE_OK) {
    return sqlite_status(db_, bind_rc_, "bind parameter " + std::to_string(bind_index_) + " of " + sqlite3_sql(stmt_));
  }
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  return sqlite_status(db_, rc, std::string("run ") + sqlite3_sql(stmt_));
}

Status Statement::run() {
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const bool row, step());
    if (!row) return ok_status();
  }
}

void Statement::reset() { sqlite3_reset(stmt_); }

int Statement::column_count() const { return sqlite3_column_count(stmt_); }
std::string Statement::column_name(int col) const {
  const char* name = sqlite3_column_name(stmt_, col);
  return name ? name : "";
}
int Statement::column_type(int col) const { return sqlite3_column_type(stmt_, col); }
bool Statement::is_null(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }
int64_t Statement::int64(int col) const { return sqlite3_column_int64(stmt_, col); }
double Statement::real(int col) const { return sqlite3_column_double(stmt_, col); }
std::optional<double> Statement::optional_real(int col) const {
  if (is_null(col)) return std::nullopt;
  return real(col);
}

std::string Statement::text(int col) const {
  const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, col));
  // Length after the text call: the conversion to text may change it.
  return p == nullptr ? std::string() : std::string(p, size_t(sqlite3_column_bytes(stmt_, col)));
}

std::string_view Statement::text_view(int col) const {
  const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, col));
  return p == nullptr ? std::string_view() : std::string_view(p, size_t(sqlite3_column_bytes(stmt_, col)));
}

std::string_view Statement::blob_view(int col) const {
  const auto* p = static_cast<const char*>(sqlite3_column_blob(stmt_, col));
  return p == nullptr ? std::string_view() : std::string_view(p, size_t(sqlite3_column_bytes(stmt_, col)));
}

std::string Statement::blob(int col) const {
  const auto* p = static_cast<const char*>(sqlite3_column_blob(stmt_, col));
  return p == nullptr ? std::string() : std::string(p, size_t(sqlite3_column_bytes(stmt_, col)));
}

}  // namespace soiq::db
