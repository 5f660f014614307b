#include "core/base/did_you_mean.h"

#include <algorithm>
#include <vector>

namespace soiq {

int edit_distance(std::string_view a, std::string_view b) {
  // Three rows suffice: a transposition looks back two rows.
  const size_t n = b.size();
  std::vector<int> before(n + 1), previous(n + 1), current(n + 1);
  for (size_t j = 0; j <= n; ++j) previous[j] = int(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = int(i);
    for (size_t j = 1; j <= n; ++j) {
      const int substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[n];
}

std::string closest_name(std::string_view text, std::span<const std::string> names) {
  // Leading dashes of options are no part of the word: "--ls" is as short as "ls".
  const size_t word = text.size() - std::min(text.find_first_not_of('-'), text.size());
  const int limit = std::min(2, std::max(1, int(word / 3)));
  std::string best;
  int best_distance = limit + 1;
  for (const std::string& name : names) {
    const int d = edit_distance(text, name);
    if (d < best_distance && name != text) {
      best = name;
      best_distance = d;
    }
  }
  return best;
}

std::string did_you_mean(std::string_view text, std::span<const std::string> names) {
  const std::string best = closest_name(text, names);
  return best.empty() ? "" : "; did you mean '" + best + "'?";
}

}  // namespace soiq
