#pragma once
// A harness's contract check: a parser that returned OK with output its header rules out is as much
// a bug as a crash, so the harness aborts and libFuzzer saves the input. Unlike assert, it stays on
// whatever the build type.

#include <cstdio>
#include <cstdlib>

namespace soiq::fuzz {

inline void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "contract broken: %s\n", what);
  std::abort();
}

}  // namespace soiq::fuzz
