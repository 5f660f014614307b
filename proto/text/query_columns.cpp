#include "proto/text/query_columns.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "proto/text/feature_expression.h"

namespace soiq::proto_text {

const std::vector<std::string>& structure_columns() {
  static const std::vector<std::string> kColumns = {"id", "patient_id", "study_uid", "name", "laterality"};
  return kColumns;
}

QueryColumns query_columns(const v1::QueryRequest& r) {
  std::vector<std::string> all;
  for (const auto& p : r.where()) all.push_back(feature_text(p.feature()));
  for (const auto& f : r.select()) all.push_back(feature_text(f));
  if (r.has_order_by()) all.push_back(feature_text(r.order_by()));
  QueryColumns c;
  c.header = structure_columns();
  for (size_t i = 0; i < all.size(); ++i) {
    if (std::find(c.header.begin() + long(structure_columns().size()), c.header.end(), all[i]) != c.header.end())
      continue;
    c.header.push_back(all[i]);
    c.value_at.push_back(i);
  }
  return c;
}

std::string number_text(double value) {
  if (!std::isfinite(value)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", value);
  return buf;
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    const std::string& f = fields[i];
    if (f.find_first_of(",\"\n\r") == std::string::npos) {
      line += f;
      continue;
    }
    line += '"';
    for (const char ch : f) line += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    line += '"';
  }
  return line + "\n";
}

std::string csv_numbers(const std::vector<double>& values) {
  std::string text;
  for (size_t k = 0; k < values.size(); ++k) text += (k ? ";" : "") + number_text(values[k]);
  return text;
}

}  // namespace soiq::proto_text
