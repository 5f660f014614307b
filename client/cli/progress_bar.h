#pragma once
// A one-line progress bar on stderr, "stage2  300/1000 [#########.....]  120/s, 6 s left", redrawn in
// place with '\r', shown only when stdout and stderr are terminals and --quiet is not given (so logs
// and pipes stay clean). The rate
// and the time left are measured from the first update of the current stage. clear() erases it
// before anything else is written to stderr. Not thread-safe.

#include <chrono>
#include <cstdint>
#include <string>

namespace soiq::cli {

class ProgressBar {
 public:
  ProgressBar();  // enabled iff isatty(stdout) && isatty(stderr) && !quiet()
  explicit ProgressBar(bool enabled) : enabled_(enabled) {}
  void update(const std::string& stage, int64_t done, int64_t total);
  void clear();

  // The text of one state, without '\r': "stage2  3/4 [###############.....]" (30 cells), then,
  // once `elapsed_s` is at least half a second and something is done, the rate and the time left:
  // "  12/s, 8 s left" (minutes past 90 s).
  static std::string line(const std::string& stage, int64_t done, int64_t total, double elapsed_s = 0);

 private:
  bool enabled_;
  size_t drawn_ = 0;  // characters on the line now
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_;
};

}  // namespace soiq::cli
