#include "core/regions/ball_morphology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/base/cpu_dispatch.h"

namespace soiq {
namespace {

struct Offset {
  int64_t dj, dk, di_max;
};

// The squared distance exactly as the separable transform forms it: the i pass first, then j,
// then k, each adding one rounded square (distance_transform.cpp).
double squared_mm(int64_t di, int64_t dj, int64_t dk, const Vec3& h) {
  const double x = double(di) * h[0], y = double(dj) * h[1], z = double(dk) * h[2];
  const double d1 = x * x + 0.0;
  const double d2 = y * y + d1;
  return z * z + d2;
}

// Calls f(dj, dk) for each (dj, dk) line offset in the ball, limited to the grid's extent (an
// offset beyond it reaches no line), until f returns false. So a radius far beyond the grid costs
// what the whole grid costs, never more, and never overflows an integer.
template <typename F>
void for_each_offset_line(const Vec3& h, double r, const std::array<int64_t, 3>& dims, F&& f) {
  const double r2 = r * r * (1 + 1e-12);  // regions.h's tie tolerance
  auto reach = [&](double spacing, int64_t n) { return int64_t(std::min(std::ceil(r / spacing) + 1, double(n))); };
  const int64_t mj = reach(h[1], dims[1]), mk = reach(h[2], dims[2]);
  for (int64_t dk = -mk; dk <= mk; ++dk) {
    for (int64_t dj = -mj; dj <= mj; ++dj) {
      if (squared_mm(0, dj, dk, h) <= r2 && !f(dj, dk)) return;
    }
  }
}

// The ball's line offsets and each one's largest |di| (at most nx: a half-width beyond it covers
// every line whole).
std::vector<Offset> ball_offsets(const Vec3& h, double r, const std::array<int64_t, 3>& dims) {
  const double r2 = r * r * (1 + 1e-12);
  const int64_t mi = dims[0];
  std::vector<Offset> out;
  for_each_offset_line(h, r, dims, [&](int64_t dj, int64_t dk) {
    int64_t m = int64_t(std::min(std::sqrt(std::max(0.0, r2 - squared_mm(0, dj, dk, h))) / h[0], double(mi)));
    while (m > 0 && squared_mm(m, dj, dk, h) > r2) --m;
    while (m < mi && squared_mm(m + 1, dj, dk, h) <= r2) ++m;
    out.push_back({dj, dk, m});
    return true;
  });
  return out;
}

// What a dilation and an erosion share: the ball's line offsets, the result on the structure's grid
// (its line table sized), and a difference array over one line, cleared between lines.
struct BallPass {
  BallPass(const RunLengthVolume& s, double radius_mm)
      : offsets(ball_offsets(s.geometry.spacing_mm, radius_mm, s.geometry.dims)),
        delta(size_t(s.geometry.dims[0]) + 1, 0) {
    out.geometry = s.geometry;
    out.line_start.assign(size_t(s.line_count()) + 1, 0);
  }

  // Appends the stretches of [lo, hi) where the running sum of `delta` reaches `threshold` as
  // runs, and clears delta[lo..hi] for the next line.
  void append_covered(int64_t lo, int64_t hi, int32_t threshold) {
    int32_t count = 0;
    int64_t begin = -1;
    for (int64_t i = lo; i <= hi; ++i) {
      count += delta[size_t(i)];
      delta[size_t(i)] = 0;
      const bool kept = i < hi && count >= threshold;
      if (kept && begin < 0) begin = i;
      if (!kept && begin >= 0) {
        out.runs.push_back({int32_t(begin), int32_t(i)});
        begin = -1;
      }
    }
  }

  RunLengthVolume finish() {
    out.line_start.back() = int64_t(out.runs.size());
    return std::move(out);
  }

  const std::vector<Offset> offsets;
  RunLengthVolume out;
  std::vector<int32_t> delta;
};

}  // namespace

int64_t ball_offset_lines(const ImageGeometry& grid, double radius_mm, int64_t stop_at) {
  int64_t count = 0;
  for_each_offset_line(grid.spacing_mm, radius_mm, grid.dims, [&](int64_t, int64_t) { return ++count < stop_at; });
  return count;
}

static RunLengthVolume ball_dilation_here(const RunLengthVolume& s, double radius_mm) {
  const int64_t nx = s.geometry.dims[0], ny = s.geometry.dims[1], nz = s.geometry.dims[2];
  BallPass pass(s, radius_mm);
  const std::vector<Offset>& offsets = pass.offsets;
  std::vector<int32_t>& delta = pass.delta;
  RunLengthVolume& out = pass.out;
  // Lines that hold a run, and the (j, k) range the result can reach.
  int64_t jlo = ny, jhi = -1, klo = nz, khi = -1, mj = 0, mk = 0;
  for (int64_t l = 0; l < s.line_count(); ++l) {
    if (s.line_start[size_t(l)] == s.line_start[size_t(l) + 1]) continue;
    jlo = std::min(jlo, l % ny), jhi = std::max(jhi, l % ny), klo = std::min(klo, l / ny), khi = std::max(khi, l / ny);
  }
  for (const Offset& o : offsets) mj = std::max(mj, std::abs(o.dj)), mk = std::max(mk, std::abs(o.dk));
  // The union of a line's pieces by a difference array over their span, O(pieces + span): no
  // sort. A count that stays positive across a piece's end joins adjacent pieces into one run
  // (runs are non-adjacent).
  for (int64_t l = 0; l < s.line_count(); ++l) {
    out.line_start[size_t(l)] = int64_t(out.runs.size());
    const int64_t j = l % ny, k = l / ny;
    if (jhi < 0 || j < jlo - mj || j > jhi + mj || k < klo - mk || k > khi + mk) continue;
    int64_t span_lo = nx, span_hi = 0;
    for (const Offset& o : offsets) {
      const int64_t sj = j + o.dj, sk = k + o.dk;
      if (sj < 0 || sj >= ny || sk < 0 || sk >= nz) continue;
      const int64_t sl = sj + ny * sk;
      for (int64_t r = s.line_start[size_t(sl)]; r < s.line_start[size_t(sl) + 1]; ++r) {
        const Run& run = s.runs[size_t(r)];
        const int64_t b = std::max<int64_t>(0, run.begin - o.di_max), e = std::min<int64_t>(nx, run.end + o.di_max);
        ++delta[size_t(b)], --delta[size_t(e)];
        span_lo = std::min(span_lo, b), span_hi = std::max(span_hi, e);
      }
    }
    pass.append_covered(span_lo, span_hi, 1);
  }
  return pass.finish();
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
RunLengthVolume ball_dilation(const RunLengthVolume& s, double radius_mm) {
  return cpu_dispatch([&] { return ball_dilation_here(s, radius_mm); });
}

static RunLengthVolume ball_erosion_here(const RunLengthVolume& s, double radius_mm) {
  const int64_t nx = s.geometry.dims[0], ny = s.geometry.dims[1], nz = s.geometry.dims[2];
  BallPass pass(s, radius_mm);
  const std::vector<Offset>& offsets = pass.offsets;
  std::vector<int32_t>& delta = pass.delta;
  RunLengthVolume& out = pass.out;
  for (int64_t k = 0, l = 0; k < nz; ++k) {
    for (int64_t j = 0; j < ny; ++j, ++l) {
      out.line_start[size_t(l)] = int64_t(out.runs.size());
      const int64_t first = s.line_start[size_t(l)], last = s.line_start[size_t(l) + 1];
      if (first == last) continue;  // the result lies inside the structure
      // A neighbour line in the grid without runs is all outside: nothing of this line survives.
      bool possible = true;
      for (size_t o = 0; o < offsets.size() && possible; ++o) {
        const int64_t sj = j + offsets[o].dj, sk = k + offsets[o].dk;
        if (sj < 0 || sj >= ny || sk < 0 || sk >= nz) continue;
        const int64_t sl = sj + ny * sk;
        possible = s.line_start[size_t(sl)] != s.line_start[size_t(sl) + 1];
      }
      if (!possible) continue;
      // Voxel i survives a neighbour line iff [i - w, i + w], clipped to the grid, lies in one of
      // its runs [b, e): i in [b + w, e - w), with no shrinking at a grid end (nothing is outside
      // there). Counted over this line's own span, which the offset (0, 0) bounds anyway.
      const int64_t span_lo = s.runs[size_t(first)].begin, span_hi = s.runs[size_t(last) - 1].end;
      int32_t needed = 0;
      for (const Offset& o : offsets) {
        const int64_t sj = j + o.dj, sk = k + o.dk;
        if (sj < 0 || sj >= ny || sk < 0 || sk >= nz) continue;
        ++needed;
        const int64_t sl = sj + ny * sk;
        for (int64_t r = s.line_start[size_t(sl)]; r < s.line_start[size_t(sl) + 1]; ++r) {
          const Run& run = s.runs[size_t(r)];
          const int64_t b = std::max(span_lo, run.begin == 0 ? 0 : run.begin + o.di_max);
          const int64_t e = std::min(span_hi, run.end == nx ? nx : run.end - o.di_max);
          if (b < e) ++delta[size_t(b)], --delta[size_t(e)];
        }
      }
      // At most one piece per neighbour line covers a voxel: reaching `needed` means all do.
      pass.append_covered(span_lo, span_hi, needed);
    }
  }
  return pass.finish();
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
RunLengthVolume ball_erosion(const RunLengthVolume& s, double radius_mm) {
  return cpu_dispatch([&] { return ball_erosion_here(s, radius_mm); });
}

}  // namespace soiq
