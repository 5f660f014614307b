#pragma once
// A conjunction of SQL conditions with their bound parameters, for the queries whose filters are
// optional (list_* and stage1): each added condition takes the next ?n, and bind() binds them all.
// Column names are code constants, never input; every input value goes through a parameter.

#include <string>
#include <variant>
#include <vector>

#include "db/sqlite/sqlite_statement.h"

namespace soiq::db {

class SqlConditions {
 public:
  struct NumberComparison {
    std::string column;
    std::string op;  // an SQL comparison operator
    double value = 0;
  };
  // "key IN (SELECT key FROM table WHERE alternative UNION ALL SELECT key FROM table WHERE c1 op v1
  // AND c2 op v2 …)": the comparisons hold, or `alternative` (a parameterless condition) says they do
  // not apply to the row. Two searches of `table`, each by its own index, whatever SQLite believes
  // of the outer query's other conditions (sqlite_store_stage1.cpp says why).
  void all_unless(const std::string& key, const std::string& table, const std::string& alternative,
                  const std::vector<NumberComparison>& comparisons);
  // "column = value"
  void equal(const std::string& column, const std::string& value);
  // "column op value" for op in <, <=, >, >=
  void compare(const std::string& column, const char* op, const std::string& value);
  void compare(const std::string& column, const char* op, double value);
  // "column GLOB pattern", plus the index range of the pattern's literal prefix (glob_range.h).
  void glob(const std::string& column, const std::string& pattern);
  // A condition with one parameter written as "?"; e.g. "st.pk IN (… WHERE modality = ? …)" where
  // every "?" is the same value.
  void with_parameter(const std::string& condition_with_question_marks, const std::string& value);

  // " AND c1 AND c2 …" (empty when there is no condition), to follow a WHERE clause.
  std::string sql() const;
  void bind(Statement& st) const;

 private:
  std::string next();  // the next parameter, "?n"

  std::vector<std::string> conditions_;
  std::vector<std::variant<std::string, double>> params_;
};

}  // namespace soiq::db
