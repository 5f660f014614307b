#include "client/cli/row_printer.h"

#include <algorithm>
#include <cmath>

#include "proto/text/query_columns.h"

namespace soiq::cli {

using proto_text::number_text;

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", c);
      out += esc;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

Cell text_cell(const std::string& text) { return {text, json_string(text)}; }
Cell int_cell(long long value) { return {std::to_string(value), std::to_string(value)}; }
Cell number_cell(double value) { return {number_text(value), number_text(value)}; }

Cell numbers_cell(const std::vector<double>& values, bool csv) {
  if (values.size() == 1) return number_cell(values[0]);
  Cell c;
  if (csv) c.text = proto_text::csv_numbers(values);
  if (!csv) c.text.push_back('(');
  c.json.push_back('[');
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) {
      if (!csv) c.text += ", ";
      c.json += ", ";
    }
    if (!csv) c.text += number_text(values[i]);
    c.json += number_text(values[i]);
  }
  if (!csv) c.text.push_back(')');
  c.json.push_back(']');
  return c;
}

Status check_row_format(const std::string& format) {
  if (format == "table" || format == "json" || format == "csv") return ok_status();
  return invalid_argument("--format must be table, json or csv, got '" + format + "'");
}

RowPrinter::RowPrinter(std::string format, std::vector<std::string> header, FILE* out)
    : format_(std::move(format)), header_(std::move(header)), out_(out) {
  if (format_ == "csv") {
    std::fputs(proto_text::csv_line(header_).c_str(), out_);
  } else if (format_ == "json") {
    std::fputc('[', out_);
  }
}

void RowPrinter::row(const std::vector<Cell>& cells) {
  if (format_ == "table") {
    std::vector<std::string> texts;
    for (const Cell& c : cells) texts.push_back(c.text);
    held_.push_back(std::move(texts));
  } else if (format_ == "csv") {
    std::vector<std::string> texts;
    for (const Cell& c : cells) texts.push_back(c.text);
    std::fputs(proto_text::csv_line(texts).c_str(), out_);
  } else {
    std::fprintf(out_, "%s\n  {", count_ ? "," : "");
    for (size_t i = 0; i < cells.size() && i < header_.size(); ++i) {
      std::fprintf(out_, "%s%s: %s", i ? ", " : "", json_string(header_[i]).c_str(), cells[i].json.c_str());
    }
    std::fputc('}', out_);
  }
  ++count_;
  std::fflush(out_);
}

void RowPrinter::end() {
  if (format_ == "json") {
    std::fputs(count_ ? "\n]\n" : "]\n", out_);
    return;
  }
  if (format_ != "table") return;
  std::vector<size_t> width(header_.size());
  for (size_t c = 0; c < header_.size(); ++c) width[c] = header_[c].size();
  for (const auto& r : held_) {
    for (size_t c = 0; c < r.size() && c < width.size(); ++c) width[c] = std::max(width[c], r[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string text;
    for (size_t c = 0; c < cells.size() && c < width.size(); ++c) {
      text += cells[c];
      if (c + 1 < cells.size()) text += std::string(width[c] - cells[c].size() + 2, ' ');
    }
    std::fprintf(out_, "%s\n", text.c_str());
  };
  line(header_);
  for (const auto& r : held_) line(r);
}

}  // namespace soiq::cli
