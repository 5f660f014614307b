#include "core/voxelize/coverage_line.h"

#include <algorithm>
#include <cmath>

namespace soiq {

bool sample_line_events(SampleCrossing* first, SampleCrossing* last, FillRule rule,
                        std::vector<CoverageEvent>& events) {
  std::sort(first, last, [](const SampleCrossing& a, const SampleCrossing& b) { return a.x < b.x; });
  int32_t winding = 0;
  bool inside = false;
  // Crossings at the same x may come in any order: a momentary flip between them is an empty
  // interval, which adds nothing to any voxel.
  for (SampleCrossing* c = first; c < last; ++c) {
    winding = rule == FillRule::kNonZero ? winding + c->sign : winding ^ 1;
    const bool now = winding != 0;
    if (now == inside) continue;
    inside = now;
    events.push_back({c->x, now ? 1 : -1});
  }
  if (inside) events.push_back({HUGE_VAL, -1});
  return winding == 0;
}

namespace coverage_line_detail {

// Accumulates the pieces of one voxel at a time, in increasing i, and emits it when the sweep
// moves past it.
class RowWriter {
 public:
  RowWriter(int samples, int64_t line_first_full, std::vector<Run>& full, std::vector<PartialVoxel>& partial)
      : samples_(samples), line_first_full_(line_first_full), full_(full), partial_(partial) {}

  // `length` of voxel i covered by `count` of the sample lines.
  void add_piece(int64_t i, double length, int count) {
    if (i != voxel_) {
      flush();
      voxel_ = i;
    }
    covered_ += length * count;
    uncovered_ += length * (samples_ - count);
  }

  // Voxels [begin, end), wholly between two events, each covered by `count` sample lines.
  void add_whole(int64_t begin, int64_t end, int count) {
    if (begin >= end || count == 0) return;
    flush();
    if (count == samples_) {
      append_full(begin, end);
      return;
    }
    const float f = float(double(count) / samples_);
    for (int64_t i = begin; i < end; ++i) partial_.push_back({int32_t(i), f});
  }

  void flush() {
    if (voxel_ < 0) return;
    if (uncovered_ == 0 && covered_ > 0) {
      append_full(voxel_, voxel_ + 1);
    } else if (covered_ > 0) {
      // Normalised by the voxel's own pieces, which sum to its width up to rounding.
      float f = float(covered_ / (covered_ + uncovered_));
      f = std::clamp(f, std::nextafter(0.f, 1.f), std::nextafter(1.f, 0.f));
      partial_.push_back({int32_t(voxel_), f});
    }
    voxel_ = -1;
    covered_ = uncovered_ = 0;
  }

 private:
  void append_full(int64_t begin, int64_t end) {
    if (int64_t(full_.size()) > line_first_full_ && full_.back().end == begin) {
      full_.back().end = int32_t(end);
      return;
    }
    full_.push_back({int32_t(begin), int32_t(end)});
  }

  const int samples_;
  const int64_t line_first_full_;
  std::vector<Run>& full_;
  std::vector<PartialVoxel>& partial_;
  int64_t voxel_ = -1;
  double covered_ = 0, uncovered_ = 0;
};

}  // namespace coverage_line_detail

void cover_line(std::vector<CoverageEvent>& events, int64_t nx, int samples, int64_t line_first_full,
                std::vector<Run>& full, std::vector<PartialVoxel>& partial) {
  std::sort(events.begin(), events.end(), [](const CoverageEvent& a, const CoverageEvent& b) { return a.x < b.x; });
  coverage_line_detail::RowWriter row(samples, line_first_full, full, partial);
  const double row_begin = -0.5, row_end = double(nx) - 0.5;
  // The voxels [x0, x1) touches, x0 < x1 within the row, all covered by `count` sample lines.
  auto sweep = [&](double x0, double x1, int count) {
    if (!(x1 > x0)) return;
    const int64_t v0 = std::min<int64_t>(int64_t(std::floor(x0 + 0.5)), nx - 1);
    // x + 1/2 rounds: a piece a few ulps long just below a voxel boundary can see its start rounded
    // up into the next voxel and its end not. It then belongs to v0 alone: the sweep must never go
    // back to a voxel it has left (that voxel would be written twice).
    const int64_t v1 = std::max(v0, std::min<int64_t>(int64_t(std::ceil(x1 + 0.5)) - 1, nx - 1));
    if (v0 == v1) {
      row.add_piece(v0, x1 - x0, count);
      return;
    }
    row.add_piece(v0, (double(v0) + 0.5) - x0, count);
    row.add_whole(v0 + 1, v1, count);
    row.add_piece(v1, x1 - (double(v1) - 0.5), count);
  };
  int count = 0;
  double at = row_begin;
  for (const CoverageEvent& e : events) {
    const double x = std::clamp(e.x, row_begin, row_end);
    sweep(at, x, count);
    at = std::max(at, x);
    count += e.delta;
  }
  sweep(at, row_end, count);
  row.flush();
}

}  // namespace soiq
