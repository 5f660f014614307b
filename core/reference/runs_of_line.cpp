#include "core/reference/runs_of_line.h"

namespace soiq {

std::vector<Run> runs_of_line(const uint8_t* inside, int64_t nx) {
  std::vector<Run> runs;
  int64_t i = 0;
  while (i < nx) {
    while (i < nx && inside[i] == 0) ++i;
    if (i == nx) break;
    const int64_t begin = i;
    while (i < nx && inside[i] != 0) ++i;
    runs.push_back({int32_t(begin), int32_t(i)});
  }
  return runs;
}

}  // namespace soiq
