#include "db/sql/glob_range.h"

#include <string_view>

namespace soiq::db {

GlobRange glob_range(const std::string& pattern) {
  GlobRange r;
  r.lower = pattern.substr(0, pattern.find_first_of("*?["));
  // The smallest string above every string that starts with the prefix: drop trailing 0xFF bytes
  // (nothing follows them) and increment the last remaining byte.
  std::string upper = r.lower;
  while (!upper.empty() && static_cast<unsigned char>(upper.back()) == 0xff) upper.pop_back();
  if (!upper.empty()) {
    upper.back() = char(static_cast<unsigned char>(upper.back()) + 1);
    r.upper = upper;
  }
  return r;
}

std::string glob_regex(const std::string& pattern) {
  // "a^": an 'a' before the start of the text, which no text has.
  static const std::string kNothing = "a^";
  std::string re = "^";
  for (size_t i = 0; i < pattern.size(); ++i) {
    const char ch = pattern[i];
    if (ch == '*') {
      re += ".*";
    } else if (ch == '?') {
      re += '.';
    } else if (ch == '[') {
      // SQLite: after '[' an optional '^', then a ']' right there is a member, then up to ']'.
      size_t j = i + 1;
      std::string set = "[";
      if (j < pattern.size() && pattern[j] == '^') set += '^', ++j;
      if (j < pattern.size() && pattern[j] == ']') set += ']', ++j;
      for (; j < pattern.size() && pattern[j] != ']'; ++j) {
        // In a bracket expression of an ARE a backslash escapes, and "[:" "[." "[=" open classes.
        if (pattern[j] == '\\' || pattern[j] == '[') set += '\\';
        set += pattern[j];
      }
      if (j >= pattern.size()) return kNothing;
      re += set + ']';
      i = j;
    } else {
      if (std::string_view("\\.^$|()[]{}*+?").find(ch) != std::string_view::npos) re += '\\';
      re += ch;
    }
  }
  return re + "$";
}

std::string ascii_lower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  }
  return s;
}

}  // namespace soiq::db
