#pragma once
// A conjunction of SQL conditions with their bound parameters, for the queries whose filters are
// optional (list_* and stage1), in either backend's dialect: each added condition takes the next
// parameter (?n, which the PostgreSQL session renumbers), and bind() binds them all. Column names are code
// constants, never input; every input value goes through a parameter.

#include <string>
#include <variant>
#include <vector>

namespace soiq::db {

enum class SqlDialect { kSqlite, kPostgres };

class SqlConditions {
 public:
  using Value = std::variant<std::string, double>;
  struct NumberComparison {
    std::string column;
    std::string op;  // an SQL comparison operator
    double value = 0;
  };

  explicit SqlConditions(SqlDialect dialect = SqlDialect::kSqlite) : dialect_(dialect) {}

  // "key IN (SELECT key FROM table WHERE alternative UNION ALL SELECT key FROM table WHERE c1 op v1
  // AND c2 op v2 …)": the comparisons hold, or `alternative` (a parameterless condition) says they do
  // not apply to the row. Two searches of `table`, each by its own index, whatever the planner
  // believes of the outer query's other conditions (sqlite_store_stage1.cpp says why).
  void all_unless(const std::string& key, const std::string& table, const std::string& alternative,
                  const std::vector<NumberComparison>& comparisons);
  // "column = value"
  void equal(const std::string& column, const std::string& value);
  // "column op value" for op in <, <=, >, >=
  void compare(const std::string& column, const char* op, const std::string& value);
  void compare(const std::string& column, const char* op, double value);
  // "column GLOB pattern" (PostgreSQL: "column ~ regex", glob_regex), plus the index range of the
  // pattern's literal prefix (glob_range.h). PostgreSQL compares text by the column's collation:
  // the store's columns are "C" (byte order), as the range assumes.
  void glob(const std::string& column, const std::string& pattern);
  // "/value/" occurs in `column` (a list such as /MR/CT/).
  void contains_delimited(const std::string& column, const std::string& value);
  // "column IN (v1, v2, …)"; no values: nothing matches.
  void any_equal(const std::string& column, const std::vector<std::string>& values);
  // "(column GLOB p1 OR column GLOB p2 …)" (PostgreSQL: regexes), without index ranges.
  void any_glob(const std::string& column, const std::vector<std::string>& patterns);
  // A condition of code with each "{}" in `sql` standing for the next of `values`, in order.
  void with_values(const std::string& sql, const std::vector<std::string>& values);
  // A parameterless condition of code.
  void literal(const std::string& sql) { conditions_.push_back(sql); }

  // sql(), then forgets the conditions but not their parameters: the next conditions go to another
  // WHERE clause of the same statement (a UNION's other half), numbered on.
  std::string take_sql();

  // " AND c1 AND c2 …" (empty when there is no condition), to follow a WHERE clause.
  std::string sql() const;
  const std::vector<Value>& params() const { return params_; }
  // Binds the parameters to a statement with bind(int, const std::string&) and bind(int, double),
  // from 1 (a SQLite statement).
  template <typename Statement>
  void bind(Statement& st) const {
    for (size_t i = 0; i < params_.size(); ++i) {
      if (const auto* text = std::get_if<std::string>(&params_[i])) {
        st.bind(int(i + 1), *text);
      } else {
        st.bind(int(i + 1), std::get<double>(params_[i]));
      }
    }
  }

 private:
  std::string next();  // the parameter for the value just added

  SqlDialect dialect_;
  std::vector<std::string> conditions_;
  std::vector<Value> params_;
};

}  // namespace soiq::db
