#include "db/sql/record_sql.h"

#include <cstdio>
#include <cstdlib>

namespace soiq::db {

std::string select_sql(std::initializer_list<std::string_view> column_lists,
                       std::initializer_list<std::string_view> rest) {
  std::string sql = "SELECT ";
  const char* separator = "";
  for (std::string_view columns : column_lists) {
    sql.append(separator).append(columns);
    separator = ", ";
  }
  for (std::string_view part : rest) sql.append(" ").append(part);
  return sql;
}

std::string parameter_list(size_t n) {
  std::string out;
  for (size_t i = 1; i <= n; ++i) out.append(i > 1 ? ", ?" : "?").append(std::to_string(i));
  return out;
}

std::string array_literal(const std::vector<int64_t>& values) {
  std::string out = "{";
  for (size_t i = 0; i < values.size(); ++i) out.append(i > 0 ? "," : "").append(std::to_string(values[i]));
  return out + "}";
}

std::string array_literal(const std::vector<std::string>& values) {
  std::string out = "{";
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out += ',';
    out += '"';
    for (const char ch : values[i]) {
      if (ch == '"' || ch == '\\') out += '\\';
      out += ch;
    }
    out += '"';
  }
  return out + "}";
}

std::string join_uid_list(const std::vector<std::string>& uids) {
  std::string out;
  for (size_t i = 0; i < uids.size(); ++i) {
    if (i) out += '\\';
    out += uids[i];
  }
  return out;
}

std::vector<std::string> split_uid_list(const std::string& joined) {
  std::vector<std::string> out;
  if (joined.empty()) return out;
  size_t start = 0;
  while (true) {
    const size_t end = joined.find('\\', start);
    out.push_back(joined.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return out;
    start = end + 1;
  }
}

std::string join_positions(const std::vector<double>& positions) {
  std::string out;
  char buf[32];
  for (size_t i = 0; i < positions.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g", positions[i]);
    if (i) out += ' ';
    out += buf;
  }
  return out;
}

std::vector<double> split_positions(const std::string& joined) {
  std::vector<double> out;
  const char* at = joined.c_str();
  while (*at != '\0') {
    char* end = nullptr;
    const double v = std::strtod(at, &end);
    if (end == at) break;
    out.push_back(v);
    at = end;
  }
  return out;
}

}  // namespace soiq::db
