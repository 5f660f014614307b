#pragma once
// Small text helpers shared by soiq's own NRRD and MetaImage header parsers: trimming, splitting and
// locale-independent number parsing. Pure functions; thread-safe.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace soiq {

// `s` without leading and trailing spaces, tabs, CR and LF.
std::string_view trim(std::string_view s);

// The whitespace-separated words of `s`.
std::vector<std::string_view> split_words(std::string_view s);

// The whole of `s` (trimmed) as a finite or non-finite double ("nan", "inf" accepted), or nullopt.
std::optional<double> parse_double(std::string_view s);

// The whole of `s` (trimmed) as an integer, or nullopt.
std::optional<long long> parse_integer(std::string_view s);

// Exactly `count` doubles separated by whitespace, commas or parentheses ("(1,0,0)" or "1 0 0"),
// or nullopt when there are more, fewer or malformed ones.
std::optional<std::vector<double>> parse_doubles(std::string_view s, size_t count);

// The directory part of `path` including its trailing slash ("" for a bare file name).
std::string directory_of(const std::string& path);

// `s` in lower case (ASCII).
std::string to_lower(std::string_view s);

}  // namespace soiq
