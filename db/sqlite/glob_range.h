#pragma once
// The key range a SQLite GLOB pattern can match, so a glob on an indexed column becomes an index
// range scan plus the GLOB test. (SQLite's own LIKE/GLOB optimisation does not apply to bound
// parameters without STAT4 nor to expression indexes such as lower(name), so we add the range.)

#include <optional>
#include <string>

namespace soiq::db {

struct GlobRange {
  std::string lower;                 // every match is >= lower (the literal prefix)
  std::optional<std::string> upper;  // and < upper; none when the prefix is empty or all 0xFF
};

// The literal prefix is the text before the first '*', '?' or '['. Byte order (BINARY collation).
GlobRange glob_range(const std::string& pattern);

// ASCII lower case, exactly what SQLite's built-in lower() does (non-ASCII bytes unchanged).
std::string ascii_lower(std::string s);

}  // namespace soiq::db
