#pragma once
// A one-line progress bar on stderr, "stage2  123/1000 [#####.....]", redrawn in place with '\r',
// shown only when stderr is a terminal (so logs and pipes stay clean). clear() erases it before
// anything else is written to stderr. Not thread-safe.

#include <cstdint>
#include <string>

namespace soiq::cli {

class ProgressBar {
 public:
  ProgressBar();  // enabled iff isatty(stderr)
  explicit ProgressBar(bool enabled) : enabled_(enabled) {}
  void update(const std::string& stage, int64_t done, int64_t total);
  void clear();

  // The text of one state, without '\r': "stage2  3/4 [###############.....]" (30 cells).
  static std::string line(const std::string& stage, int64_t done, int64_t total);

 private:
  bool enabled_;
  size_t drawn_ = 0;  // characters on the line now
};

}  // namespace soiq::cli
