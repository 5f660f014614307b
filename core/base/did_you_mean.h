#pragma once
// "Did you mean": the known name closest to a mistyped one, by Damerau-Levenshtein distance
// (insertions, deletions, substitutions and transpositions of neighbours each cost 1; the
// "optimal string alignment" variant, which edits no substring twice). Used wherever a name is
// refused: commands and options of `soiq`, feature, region and image names.
//
// Inputs: the text as given and the names it should have been one of.
// Output: edit_distance, the distance; closest_name, the nearest name within the limit
//   (distance <= 2 and <= max(1, length / 3) of the text, so "ls" never suggests "rm"), the first
//   of equals in `names` order, or "" when none is near; did_you_mean, "; did you mean 'x'?" or "".
// Cost: O(|a| |b|) per pair; pure and thread-safe.

#include <span>
#include <string>
#include <string_view>

namespace soiq {

int edit_distance(std::string_view a, std::string_view b);

std::string closest_name(std::string_view text, std::span<const std::string> names);

std::string did_you_mean(std::string_view text, std::span<const std::string> names);

}  // namespace soiq
