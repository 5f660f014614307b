#include "client/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "client/cli/quiet.h"

namespace soiq::cli {

// Both must be terminals: output sent to a file or a pipe is a script's, which wants no redraws in
// its log.
ProgressBar::ProgressBar() : enabled_(isatty(fileno(stderr)) != 0 && isatty(fileno(stdout)) != 0 && !quiet()) {}

namespace {

// "12/s" or "0.4/s": two significant figures are enough to judge a rate.
std::string rate_text(double per_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, per_s >= 10 ? "%.0f/s" : "%.1f/s", per_s);
  return buf;
}

std::string time_left_text(double s) {
  char buf[32];
  if (s < 90) {
    std::snprintf(buf, sizeof buf, "%.0f s left", std::ceil(s));
  } else {
    std::snprintf(buf, sizeof buf, "%.0f min left", std::ceil(s / 60));
  }
  return buf;
}

}  // namespace

std::string ProgressBar::line(const std::string& stage, int64_t done, int64_t total, double elapsed_s) {
  constexpr int64_t kCells = 30;
  const int64_t filled = total > 0 ? std::clamp<int64_t>(done * kCells / total, 0, kCells) : 0;
  std::string text = stage + "  " + std::to_string(done) + "/" + std::to_string(total) + " [" +
                     std::string(size_t(filled), '#') + std::string(size_t(kCells - filled), '.') + "]";
  if (elapsed_s >= 0.5 && done > 0) {
    const double per_s = double(done) / elapsed_s;
    text += "  " + rate_text(per_s);
    if (total > done) text += ", " + time_left_text(double(total - done) / per_s);
  }
  return text;
}

void ProgressBar::update(const std::string& stage, int64_t done, int64_t total) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
  }
  const std::string text = line(stage, done, total, std::chrono::duration<double>(now - stage_start_).count());
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
