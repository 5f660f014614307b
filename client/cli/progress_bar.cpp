#include "client/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace soiq::cli {

ProgressBar::ProgressBar() : enabled_(isatty(fileno(stderr)) != 0) {}

std::string ProgressBar::line(const std::string& stage, int64_t done, int64_t total) {
  constexpr int64_t kCells = 30;
  const int64_t filled = total > 0 ? std::clamp<int64_t>(done * kCells / total, 0, kCells) : 0;
  return stage + "  " + std::to_string(done) + "/" + std::to_string(total) + " [" + std::string(size_t(filled), '#') +
         std::string(size_t(kCells - filled), '.') + "]";
}

void ProgressBar::update(const std::string& stage, int64_t done, int64_t total) {
  if (!enabled_) return;
  const std::string text = line(stage, done, total);
  std::fprintf(stderr, "\r%s%s", text.c_str(),
               std::string(drawn_ > text.size() ? drawn_ - text.size() : 0, ' ').c_str());
  std::fflush(stderr);
  drawn_ = text.size();
}

void ProgressBar::clear() {
  if (!enabled_ || drawn_ == 0) return;
  std::fprintf(stderr, "\r%s\r", std::string(drawn_, ' ').c_str());
  std::fflush(stderr);
  drawn_ = 0;
}

}  // namespace soiq::cli
