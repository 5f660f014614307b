#include "db/sqlite/glob_range.h"

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

std::string ascii_lower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  }
  return s;
}

}  // namespace soiq::db
