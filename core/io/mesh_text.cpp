#include "core/io/mesh_text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

namespace soiq {
namespace {

bool is_word_separator(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// from_chars takes no leading '+'; writers that print one ("+1.5e+01") are valid, so accept a
// single '+' before a digit or a point, and nothing else from_chars would not take.
std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && (std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.')) {
    token.remove_prefix(1);
  }
  return token;
}

Result<double> parse_number(std::string_view token, std::string_view where, bool finite) {
  const std::string_view digits = without_plus(token);
  double value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = !digits.empty() && end == digits.data() + digits.size();
  if (ec == std::errc::result_out_of_range && whole) {
    return invalid_argument(std::string(where) + ": " + quoted(token) + " is out of range");
  }
  if (ec != std::errc() || !whole) {
    return invalid_argument(std::string(where) + ": " + quoted(token) + " is not a number");
  }
  if (finite && !std::isfinite(value)) {
    return invalid_argument(std::string(where) + ": " + quoted(token) + " is not a finite number");
  }
  return value;
}

}  // namespace

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  size_t end = text_.find('\n', pos_);
  const size_t stop = end == std::string_view::npos ? text_.size() : end;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++next_number_;
  return true;
}

void words_of(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_word_separator(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !is_word_separator(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
}

Result<double> finite_number(std::string_view token, std::string_view where) {
  return parse_number(token, where, /*finite=*/true);
}

Result<double> any_number(std::string_view token, std::string_view where) {
  return parse_number(token, where, /*finite=*/false);
}

Result<int64_t> whole_integer(std::string_view token, std::string_view where) {
  const std::string_view digits = without_plus(token);
  int64_t value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = !digits.empty() && end == digits.data() + digits.size();
  if (ec == std::errc::result_out_of_range && whole) {
    return invalid_argument(std::string(where) + ": " + quoted(token) + " is out of range");
  }
  if (ec != std::errc() || !whole) {
    return invalid_argument(std::string(where) + ": " + quoted(token) + " is not an integer");
  }
  return value;
}

std::string quoted(std::string_view token) {
  constexpr size_t kMaxShown = 40;
  std::string out = "'";
  for (const char c : token.substr(0, kMaxShown)) out += c >= 0x20 && c < 0x7f ? c : '?';
  if (token.size() > kMaxShown) out += "...";
  return out + "'";
}

std::string line_where(std::string_view format, const std::string& name, int64_t line) {
  return std::string(format) + " '" + name + "' line " + std::to_string(line);
}

}  // namespace soiq
