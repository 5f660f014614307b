#include "db/sqlite/sql_conditions.h"

#include "db/sqlite/glob_range.h"

namespace soiq::db {

std::string SqlConditions::next() {
  // Appending rather than "?" + to_string(): GCC 12 reports a false -Wrestrict on the latter.
  std::string p = "?";
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

void SqlConditions::glob(const std::string& column, const std::string& pattern) {
  params_.emplace_back(pattern);
  conditions_.push_back(column + " GLOB " + next());
  const GlobRange range = glob_range(pattern);
  if (!range.lower.empty()) compare(column, ">=", range.lower);
  if (range.upper) compare(column, "<", *range.upper);
}

void SqlConditions::with_parameter(const std::string& condition, const std::string& value) {
  params_.emplace_back(value);
  std::string out;
  for (char ch : condition) {
    if (ch == '?') {
      out += next();
    } else {
      out += ch;
    }
  }
  conditions_.push_back(out);
}

std::string SqlConditions::sql() const {
  std::string out;
  for (const std::string& c : conditions_) out += " AND " + c;
  return out;
}

void SqlConditions::bind(Statement& st) const {
  for (size_t i = 0; i < params_.size(); ++i) {
    if (const auto* text = std::get_if<std::string>(&params_[i])) {
      st.bind(int(i + 1), *text);
    } else {
      st.bind(int(i + 1), std::get<double>(params_[i]));
    }
  }
}

}  // namespace soiq::db
