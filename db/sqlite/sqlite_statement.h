#pragma once
// A prepared statement borrowed from a connection's cache (sqlite_connection.h) for one use: bind,
// step, read columns. On destruction it is reset and its bindings cleared, so the next borrower
// starts clean, or finalized when it was never cached. Not thread-safe: it belongs to the thread
// holding its connection.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/base/status.h"

struct sqlite3;
struct sqlite3_stmt;

namespace soiq::db {

class Statement {
 public:
  // `in_use` (may be null) is the cache's flag for this statement, cleared on destruction.
  Statement(sqlite3* db, sqlite3_stmt* stmt, bool owned, bool* in_use);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& operator=(Statement&&) = delete;

  // Parameters are 1-based, as in SQL (?1, ?2…). A failed bind is reported by the next step().
  void bind(int i, int64_t v);
  void bind(int i, double v);
  void bind(int i, std::optional<double> v);  // NULL when unset
  void bind(int i, std::string_view text);
  void bind(int i, const char* text) { bind(i, std::string_view(text)); }
  void bind_blob(int i, const void* data, size_t size);

  // true: a row is ready to read; false: the statement is done.
  Result<bool> step();
  // Steps to the end, for statements whose rows (if any) are not needed.
  Status run();
  // Back to before the first step, keeping the bindings, to run the statement again.
  void reset();

  int column_count() const;
  std::string column_name(int col) const;
  int column_type(int col) const;  // SQLite's storage class: SQLITE_INTEGER, _FLOAT, _TEXT, _BLOB, _NULL
  bool is_null(int col) const;
  int64_t int64(int col) const;
  double real(int col) const;
  std::optional<double> optional_real(int col) const;
  std::string text(int col) const;
  std::string blob(int col) const;
  // The same without a copy: valid until the next step, reset or finalisation.
  std::string_view text_view(int col) const;
  std::string_view blob_view(int col) const;

 private:
  void note_bind(int rc, int i);

  sqlite3* db_;
  sqlite3_stmt* stmt_;
  bool owned_;
  bool* in_use_;
  int bind_rc_ = 0;  // first failed bind
  int bind_index_ = 0;
};

}  // namespace soiq::db
