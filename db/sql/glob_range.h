#pragma once
// Globs (SQLite's GLOB: * ? [...] [^...], case-sensitive), which every filter of the store takes,
// in both backends: the key range a pattern can match, so a glob on an indexed column becomes an
// index range scan plus the pattern test (SQLite's own LIKE/GLOB optimisation does not apply to
// bound parameters without STAT4 nor to expression indexes such as lower(name), and PostgreSQL has
// no GLOB at all); and the same pattern as a PostgreSQL regular expression.

#include <optional>
#include <string>

namespace soiq::db {

struct GlobRange {
  std::string lower;                 // every match is >= lower (the literal prefix)
  std::optional<std::string> upper;  // and < upper; none when the prefix is empty or all 0xFF
};

// The literal prefix is the text before the first '*', '?' or '['. Byte order (BINARY collation).
GlobRange glob_range(const std::string& pattern);

// The pattern as an anchored PostgreSQL (ARE) regular expression that matches exactly the strings
// the glob matches: * -> .*, ? -> ., a bracket set copied with its backslashes and '[' escaped,
// every other character literal. An unterminated '[' matches nothing, as in SQLite.
std::string glob_regex(const std::string& pattern);

// ASCII lower case, exactly what SQLite's built-in lower() does (non-ASCII bytes unchanged).
std::string ascii_lower(std::string s);

}  // namespace soiq::db
