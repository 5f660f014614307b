#include "db/postgres/pg_session.h"

#include <endian.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace soiq::db {

PgNumberedSql pg_numbered_parameters(std::string_view sql) {
  // The numbers the text uses, then the text with each replaced by its rank among them.
  std::vector<int> used;
  for (size_t i = 0; i + 1 < sql.size(); ++i) {
    if (sql[i] != '?' || !std::isdigit(static_cast<unsigned char>(sql[i + 1]))) continue;
    int n = 0;
    for (size_t j = i + 1; j < sql.size() && std::isdigit(static_cast<unsigned char>(sql[j])); ++j)
      n = std::min(n * 10 + (sql[j] - '0'), 1 << 20);
    if (size_t(n) >= used.size()) used.resize(size_t(n) + 1, 0);
    used[size_t(n)] = 1;
  }
  PgNumberedSql out;
  out.numbers.assign(used.size(), 0);
  for (size_t n = 1, next = 1; n < used.size(); ++n) {
    if (used[n]) out.numbers[n] = int(next++);
  }
  for (size_t i = 0; i < sql.size(); ++i) {
    if (sql[i] == '?' && i + 1 < sql.size() && std::isdigit(static_cast<unsigned char>(sql[i + 1]))) {
      size_t j = i + 1;
      int n = 0;
      for (; j < sql.size() && std::isdigit(static_cast<unsigned char>(sql[j])); ++j)
        n = std::min(n * 10 + (sql[j] - '0'), 1 << 20);
      out.sql += '$' + std::to_string(out.numbers[size_t(n)]);
      i = j - 1;
    } else {
      out.sql += sql[i];
    }
  }
  return out;
}

namespace {

// PostgreSQL's type OIDs (catalog pg_type) of the columns the store reads.
constexpr unsigned kBool = 16, kBytea = 17, kInt8 = 20, kInt2 = 21, kInt4 = 23, kFloat4 = 700, kFloat8 = 701;

template <typename Int>
Int big_endian(std::string_view raw) {
  Int v = 0;
  if (raw.size() == sizeof v) std::memcpy(&v, raw.data(), sizeof v);
  if constexpr (sizeof(Int) == 8) return Int(be64toh(uint64_t(v)));
  if constexpr (sizeof(Int) == 4) return Int(be32toh(uint32_t(v)));
  if constexpr (sizeof(Int) == 2) return Int(be16toh(uint16_t(v)));
  return v;
}

class PgCursor : public SqlCursor {
 public:
  PgCursor(PgConnection& c, PgNumberedSql sql) : c_(c), sql_(std::move(sql.sql)), numbers_(std::move(sql.numbers)) {
    // Errors name the statement by its start ("INSERT INTO patients(patient_id, …").
    size_t begin = sql_.find_first_not_of(" \n");
    what_ = sql_.substr(begin == std::string::npos ? 0 : begin, 48);
    for (char& ch : what_) ch = ch == '\n' ? ' ' : ch;
  }

  void bind_null(int i) override { set(i, PgParam(std::nullopt)); }
  void bind(int i, int64_t v) override { set(i, pg_number(v)); }
  void bind(int i, double v) override { set(i, pg_number(v)); }
  void bind(int i, std::string_view text) override { set(i, std::string(text)); }
  void bind_blob(int i, std::string_view bytes) override { set(i, pg_binary_param(bytes)); }

  Result<bool> step() override {
    if (bad_bind_) return internal_error("statement parameter numbers start at 1: " + what_);
    if (!result_) {
      // Every parameter of the text is sent, those never bound as NULL.
      size_t count = 0;
      for (const int m : numbers_) count = std::max(count, size_t(m));
      if (params_.size() < count) params_.resize(count, PgParam(std::nullopt));
      SOIQ_ASSIGN_OR_RETURN(PgResult r, c_.exec_binary(sql_, params_, what_));
      result_.emplace(std::move(r));
      row_ = -1;
    }
    ++row_;
    return row_ < result_->rows();
  }
  void reset() override { result_.reset(); }

  bool is_null(int col) const override { return result_->is_null(row_, col); }
  int64_t int64(int col) const override {
    const std::string_view raw = result_->raw(row_, col);
    switch (result_->type(col)) {
      case kInt8:
        return big_endian<int64_t>(raw);
      case kInt4:
        return big_endian<int32_t>(raw);
      case kInt2:
        return big_endian<int16_t>(raw);
      case kBool:
        return raw.size() == 1 && raw[0] != 0;
      default:
        return int64_t(real(col));
    }
  }
  double real(int col) const override {
    const std::string_view raw = result_->raw(row_, col);
    switch (result_->type(col)) {
      case kFloat8: {
        const uint64_t bits = big_endian<uint64_t>(raw);
        double v = 0;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
      case kFloat4: {
        const uint32_t bits = big_endian<uint32_t>(raw);
        float v = 0;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
      case kInt8:
      case kInt4:
      case kInt2:
      case kBool:
        return double(int64(col));
      default:
        return 0;  // the store reads no other type as a number
    }
  }
  std::string_view text_view(int col) const override { return result_->raw(row_, col); }
  std::string_view blob_view(int col) const override { return result_->raw(row_, col); }
  int64_t changes() const override { return result_ ? result_->affected() : 0; }
  int column_count() const override { return result_ ? result_->columns() : 0; }
  std::string column_name(int col) const override { return result_ ? result_->column_name(col) : ""; }
  SqlValueType value_type(int col) const override {
    if (result_->is_null(row_, col)) return SqlValueType::kNull;
    switch (result_->type(col)) {
      case kBool:
      case kInt2:
      case kInt4:
      case kInt8:
        return SqlValueType::kInteger;
      case kFloat4:
      case kFloat8:
        return SqlValueType::kReal;
      case kBytea:
        return SqlValueType::kBlob;
      default:
        return SqlValueType::kText;
    }
  }

 private:
  // Parameter i of the SQLite-numbered text; one the text does not use is dropped, as SQLite
  // leaves an unused number unread.
  void set(int i, PgParam p) {
    if (i < 1) {
      bad_bind_ = true;
      return;
    }
    if (size_t(i) >= numbers_.size() || numbers_[size_t(i)] == 0) return;
    const size_t m = size_t(numbers_[size_t(i)]);
    if (m > params_.size()) params_.resize(m, PgParam(std::nullopt));
    params_[m - 1] = std::move(p);
    result_.reset();  // a new binding: the next step runs the statement again
  }

  PgConnection& c_;
  std::string sql_;
  std::vector<int> numbers_;
  std::string what_;
  bool bad_bind_ = false;
  std::vector<PgParam> params_;
  std::optional<PgResult> result_;
  int row_ = -1;
};

}  // namespace

Result<SqlStatement> PgSession::prepare(std::string_view sql) {
  return SqlStatement(std::make_unique<PgCursor>(c_, pg_numbered_parameters(sql)));
}

}  // namespace soiq::db
