#pragma once
// What the store's SQL runs on, in either backend: a session (one connection inside the unit of
// work the store opened on it) prepares statements; a statement binds parameters, steps through
// rows and reads columns. The store's records and their rules are written once against this
// (sql_store.h), as Orthanc's database plugins write their index once over a small statement
// interface with a dialect; each backend supplies a session (sqlite_session.h, pg_session.h).
//
// SQL is written with SQLite's numbered parameters (?1, ?2, …), in the subset both engines share;
// the PostgreSQL session renumbers them ($1, …). Where the dialects differ the code asks
// dialect(). Parameters are 1-based; a failed bind is reported by the next step().

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/base/status.h"
#include "db/sql/sql_conditions.h"

namespace soiq::db {

// What a column of the current row holds (for copying rows whose columns the code does not name).
enum class SqlValueType { kNull, kInteger, kReal, kText, kBlob };

// A backend's prepared statement (see SqlStatement for the meaning of each call).
class SqlCursor {
 public:
  virtual ~SqlCursor() = default;
  virtual void bind_null(int i) = 0;
  virtual void bind(int i, int64_t v) = 0;
  virtual void bind(int i, double v) = 0;
  virtual void bind(int i, std::string_view text) = 0;
  virtual void bind_blob(int i, std::string_view bytes) = 0;  // bytes must outlive the statement's steps
  virtual Result<bool> step() = 0;
  virtual void reset() = 0;
  virtual bool is_null(int col) const = 0;
  virtual int64_t int64(int col) const = 0;
  virtual double real(int col) const = 0;
  virtual std::string_view text_view(int col) const = 0;
  virtual std::string_view blob_view(int col) const = 0;
  virtual int64_t changes() const = 0;
  virtual int column_count() const = 0;
  virtual std::string column_name(int col) const = 0;
  virtual SqlValueType value_type(int col) const = 0;
};

class SqlStatement {
 public:
  explicit SqlStatement(std::unique_ptr<SqlCursor> cursor) : cursor_(std::move(cursor)) {}

  void bind(int i, int64_t v) { cursor_->bind(i, v); }
  void bind(int i, double v) { cursor_->bind(i, v); }
  void bind(int i, std::optional<double> v) { v ? cursor_->bind(i, *v) : cursor_->bind_null(i); }  // NULL when unset
  void bind(int i, std::string_view text) { cursor_->bind(i, text); }
  void bind(int i, const char* text) { cursor_->bind(i, std::string_view(text)); }
  void bind(int i, const std::string& text) { cursor_->bind(i, std::string_view(text)); }
  void bind_blob(int i, std::string_view bytes) { cursor_->bind_blob(i, bytes); }
  void bind_null(int i) { cursor_->bind_null(i); }

  // true: a row is ready to read; false: the statement is done.
  Result<bool> step() { return cursor_->step(); }
  // Steps to the end, for statements whose rows (if any) are not needed.
  Status run() {
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, step());
      if (!row) return ok_status();
    }
  }
  // Back to before the first step, keeping the bindings, to run the statement again.
  void reset() { cursor_->reset(); }
  // Rows the last run of an INSERT, UPDATE or DELETE wrote (after it is done).
  int64_t changes() const { return cursor_->changes(); }

  // The columns of the rows (after the first step), and what a column of the current row holds.
  int column_count() const { return cursor_->column_count(); }
  std::string column_name(int col) const { return cursor_->column_name(col); }
  SqlValueType value_type(int col) const { return cursor_->value_type(col); }
  bool is_null(int col) const { return cursor_->is_null(col); }
  int64_t int64(int col) const { return cursor_->int64(col); }
  double real(int col) const { return cursor_->real(col); }
  std::optional<double> optional_real(int col) const {
    return is_null(col) ? std::nullopt : std::optional<double>(real(col));
  }
  std::string text(int col) const { return std::string(cursor_->text_view(col)); }
  std::string blob(int col) const { return std::string(cursor_->blob_view(col)); }
  // The same without a copy: valid until the next step or reset.
  std::string_view text_view(int col) const { return cursor_->text_view(col); }
  std::string_view blob_view(int col) const { return cursor_->blob_view(col); }

 private:
  std::unique_ptr<SqlCursor> cursor_;
};

class SqlSession {
 public:
  virtual ~SqlSession() = default;
  virtual SqlDialect dialect() const = 0;
  virtual Result<SqlStatement> prepare(std::string_view sql) = 0;
};

}  // namespace soiq::db
