#include "db/sqlite/sqlite_session.h"

#include <sqlite3.h>

#include <memory>
#include <utility>

namespace soiq::db {
namespace {

class SqliteCursor : public SqlCursor {
 public:
  SqliteCursor(Statement st, sqlite3* db) : st_(std::move(st)), db_(db) {}
  void bind_null(int i) override { st_.bind(i, std::optional<double>()); }
  void bind(int i, int64_t v) override { st_.bind(i, v); }
  void bind(int i, double v) override { st_.bind(i, v); }
  void bind(int i, std::string_view text) override { st_.bind(i, text); }
  void bind_blob(int i, std::string_view bytes) override { st_.bind_blob(i, bytes.data(), bytes.size()); }
  Result<bool> step() override { return st_.step(); }
  void reset() override { st_.reset(); }
  bool is_null(int col) const override { return st_.is_null(col); }
  int64_t int64(int col) const override { return st_.int64(col); }
  double real(int col) const override { return st_.real(col); }
  std::string_view text_view(int col) const override { return st_.text_view(col); }
  std::string_view blob_view(int col) const override { return st_.blob_view(col); }
  // The connection's count, which is the last finished statement's: the session's statements run
  // one at a time on it.
  int64_t changes() const override { return sqlite3_changes64(db_); }
  int column_count() const override { return st_.column_count(); }
  std::string column_name(int col) const override { return st_.column_name(col); }
  SqlValueType value_type(int col) const override {
    switch (st_.column_type(col)) {
      case SQLITE_INTEGER:
        return SqlValueType::kInteger;
      case SQLITE_FLOAT:
        return SqlValueType::kReal;
      case SQLITE_TEXT:
        return SqlValueType::kText;
      case SQLITE_BLOB:
        return SqlValueType::kBlob;
      default:
        return SqlValueType::kNull;
    }
  }

 private:
  Statement st_;
  sqlite3* db_;
};

}  // namespace

Result<SqlStatement> SqliteSession::prepare(std::string_view sql) {
  SOIQ_ASSIGN_OR_RETURN(Statement st, c_.prepare(sql));
  return SqlStatement(std::make_unique<SqliteCursor>(std::move(st), c_.handle()));
}

}  // namespace soiq::db
