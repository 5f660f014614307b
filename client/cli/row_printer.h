#pragma once
// Rows of records on stdout in one of three formats, for `soiq ls` and `soiq query`:
//   table  aligned columns under a header (rows are held until end(): widths need them all)
//   csv    a header line, then one line per row as it comes (RFC 4180 quoting where needed)
//   json   one array of objects keyed by the header, each row written as it comes
// A cell carries its text for table and csv and its JSON value (a quoted string, a number, an
// array or null). Not thread-safe.

#include <cstdio>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::cli {

struct Cell {
  std::string text;  // table and csv
  std::string json;  // a JSON value
};

Cell text_cell(const std::string& text);
Cell int_cell(long long value);
// %.10g; NaN and infinities print as "null" (in JSON too).
Cell number_cell(double value);
// One value as number_cell, several as "(a, b)" in a table, "a;b" in csv, [a, b] in JSON.
Cell numbers_cell(const std::vector<double>& values, bool csv);

// INVALID_ARGUMENT unless `format` is table, json or csv.
Status check_row_format(const std::string& format);

class RowPrinter {
 public:
  RowPrinter(std::string format, std::vector<std::string> header, FILE* out = stdout);
  void row(const std::vector<Cell>& cells);
  // Writes what is held (table) or closes the array (json). Call once.
  void end();
  size_t rows() const { return count_; }

 private:
  std::string format_;
  std::vector<std::string> header_;
  FILE* out_;
  std::vector<std::vector<std::string>> held_;
  size_t count_ = 0;
};

// A JSON string literal of `text` (quotes, backslashes and control characters escaped).
std::string json_string(const std::string& text);

}  // namespace soiq::cli
