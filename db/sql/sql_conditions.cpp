#include "db/sql/sql_conditions.h"

#include "db/sql/glob_range.h"

namespace soiq::db {

std::string SqlConditions::next() {
  // Appending rather than "?" + to_string(): GCC 12 reports a false -Wrestrict on the latter.
  std::string p = "?";  // in both dialects: the PostgreSQL session renumbers (sql_session.h)
  p += std::to_string(params_.size());
  return p;
}

void SqlConditions::equal(const std::string& column, const std::string& value) { compare(column, "=", value); }

void SqlConditions::compare(const std::string& column, const char* op, const std::string& value) {
  params_.emplace_back(value);
  conditions_.push_back(column + " " + op + " " + next());
}

void SqlConditions::compare(const std::string& column, const char* op, double value) {
  params_.emplace_back(value);
  conditions_.push_back(column + " " + op + " " + next());
}

void SqlConditions::all_unless(const std::string& key, const std::string& table, const std::string& alternative,
                               const std::vector<NumberComparison>& comparisons) {
  std::string all;
  for (const NumberComparison& c : comparisons) {
    params_.emplace_back(c.value);
    all += (all.empty() ? "" : " AND ") + c.column + " " + c.op + " " + next();
  }
  conditions_.push_back(key + " IN (SELECT " + key + " FROM " + table + " WHERE " + alternative + " UNION ALL SELECT " +
                        key + " FROM " + table + " WHERE " + all + ")");
}

namespace {

bool ascii(const std::string& s) {
  for (const char c : s) {
    if (static_cast<unsigned char>(c) >= 0x80) return false;
  }
  return true;
}

}  // namespace

void SqlConditions::glob(const std::string& column, const std::string& pattern) {
  if (dialect_ == SqlDialect::kSqlite) {
    params_.emplace_back(pattern);
    conditions_.push_back(column + " GLOB " + next());
  } else {
    params_.emplace_back(glob_regex(pattern));
    conditions_.push_back(column + " ~ " + next());
  }
  const GlobRange range = glob_range(pattern);
  if (!range.lower.empty()) compare(column, ">=", range.lower);
  // PostgreSQL refuses text that is not UTF-8, which an incremented non-ASCII byte may leave: the
  // range then has no upper end (the pattern test still decides).
  if (range.upper && (dialect_ == SqlDialect::kSqlite || ascii(*range.upper))) compare(column, "<", *range.upper);
}

void SqlConditions::contains_delimited(const std::string& column, const std::string& value) {
  params_.emplace_back(value);
  const char* position = dialect_ == SqlDialect::kSqlite ? "instr(" : "strpos(";
  conditions_.push_back(position + column + ", '/' || " + next() + " || '/') > 0");
}

void SqlConditions::any_equal(const std::string& column, const std::vector<std::string>& values) {
  if (values.empty()) {
    conditions_.push_back("false");
    return;
  }
  std::string list;
  for (const std::string& v : values) {
    params_.emplace_back(v);
    list += (list.empty() ? "" : ", ") + next();
  }
  conditions_.push_back(column + " IN (" + list + ")");
}

void SqlConditions::any_glob(const std::string& column, const std::vector<std::string>& patterns) {
  if (patterns.empty()) {
    conditions_.push_back("false");
    return;
  }
  std::string any;
  for (const std::string& p : patterns) {
    params_.emplace_back(dialect_ == SqlDialect::kSqlite ? p : glob_regex(p));
    any += (any.empty() ? "" : " OR ") + column + (dialect_ == SqlDialect::kSqlite ? " GLOB " : " ~ ") + next();
  }
  conditions_.push_back("(" + any + ")");
}

void SqlConditions::with_values(const std::string& sql, const std::vector<std::string>& values) {
  std::string out;
  size_t from = 0, used = 0;
  for (size_t at = sql.find("{}"); at != std::string::npos; at = sql.find("{}", from)) {
    out += sql.substr(from, at - from);
    params_.emplace_back(used < values.size() ? values[used] : std::string());
    ++used;
    out += next();
    from = at + 2;
  }
  conditions_.push_back(out + sql.substr(from));
}

std::string SqlConditions::take_sql() {
  std::string out = sql();
  conditions_.clear();
  return out;
}

std::string SqlConditions::sql() const {
  std::string out;
  for (const std::string& c : conditions_) out += " AND " + c;
  return out;
}

}  // namespace soiq::db
