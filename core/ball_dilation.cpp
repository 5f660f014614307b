#include "core/ball_dilation.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

std::vector<Offset> ball_offsets(const Vec3& h, double r) {
  const double r2 = r * r * (1 + 1e-12);  // regions.h's tie tolerance
  std::vector<Offset> out;
  const int64_t mj = int64_t(std::ceil(r / h[1])) + 1, mk = int64_t(std::ceil(r / h[2])) + 1;
  for (int64_t dk = -mk; dk <= mk; ++dk) {
    for (int64_t dj = -mj; dj <= mj; ++dj) {
      if (squared_mm(0, dj, dk, h) > r2) continue;
      int64_t m = int64_t(std::sqrt(std::max(0.0, r2 - squared_mm(0, dj, dk, h))) / h[0]);
      while (m > 0 && squared_mm(m, dj, dk, h) > r2) --m;
      while (squared_mm(m + 1, dj, dk, h) <= r2) ++m;
      out.push_back({dj, dk, m});
    }
  }
  return out;
}

}  // namespace

int64_t ball_dilation_offsets(const ImageGeometry& grid, double radius_mm) {
  return int64_t(ball_offsets(grid.spacing_mm, radius_mm).size());
}

RunLengthVolume ball_dilation(const RunLengthVolume& s, double radius_mm) {
  const ImageGeometry& g = s.geometry;
  const int64_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
  const std::vector<Offset> offsets = ball_offsets(g.spacing_mm, radius_mm);
  RunLengthVolume out;
  out.geometry = g;
  out.line_start.assign(size_t(s.line_count()) + 1, 0);
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
  std::vector<int32_t> delta(size_t(nx) + 1, 0);
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
    int32_t count = 0;
    int64_t begin = -1;
    for (int64_t i = span_lo; i <= span_hi; ++i) {
      count += delta[size_t(i)];
      delta[size_t(i)] = 0;
      if (count > 0 && begin < 0) begin = i;
      if (count == 0 && begin >= 0) {
        out.runs.push_back({int32_t(begin), int32_t(i)});
        begin = -1;
      }
    }
  }
  out.line_start.back() = int64_t(out.runs.size());
  return out;
}

}  // namespace soiq
