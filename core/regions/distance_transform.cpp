#include "core/regions/distance_transform.h"

#include <cmath>
#include <limits>
#include <string>

#include "core/base/cpu_dispatch.h"
#include "core/base/parallel_for.h"

namespace soiq {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Scratch of one thread for the 1D transform of lines up to n long.
struct LineScratch {
  explicit LineScratch(int64_t n) : f(size_t(n)), d(size_t(n)), v(size_t(n)), z(size_t(n) + 1) {}
  std::vector<double> f, d;
  std::vector<int64_t> v;  // positions of the parabolas of the lower envelope
  std::vector<double> z;   // boundaries between them, in mm
};

// d[q] = min_p f[p] + ((q - p) h)^2 over the finite f[p]: the lower envelope of parabolas with
// apexes at p h mm (Felzenszwalb & Huttenlocher, Algorithm 1, with positions in mm). Infinite
// samples are skipped: they would give NaN intersections and can never be the minimum.
void transform_line(int64_t n, double h, LineScratch& s) {
  const double* f = s.f.data();
  int64_t k = -1;
  for (int64_t q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    const double q_mm = double(q) * h;
    if (k < 0) {
      k = 0;
      s.v[0] = q;
      s.z[0] = -kInf;
      s.z[1] = kInf;
      continue;
    }
    double cut = 0;
    // z[0] is -inf, so the loop stops with k >= 0.
    while (true) {
      const int64_t p = s.v[size_t(k)];
      const double p_mm = double(p) * h;
      cut = ((f[q] + q_mm * q_mm) - (f[p] + p_mm * p_mm)) / (2.0 * (q_mm - p_mm));
      if (cut <= s.z[size_t(k)]) {
        --k;
      } else {
        break;
      }
    }
    ++k;
    s.v[size_t(k)] = q;
    s.z[size_t(k)] = cut;
    s.z[size_t(k) + 1] = kInf;
  }
  if (k < 0) {
    for (int64_t q = 0; q < n; ++q) s.d[size_t(q)] = kInf;
    return;
  }
  int64_t j = 0;
  for (int64_t q = 0; q < n; ++q) {
    const double q_mm = double(q) * h;
    while (s.z[size_t(j) + 1] < q_mm) ++j;
    const int64_t p = s.v[size_t(j)];
    // Formed as (q - p) h, as a brute force would, so ties with a radius are decided alike.
    const double dq = double(q - p) * h;
    s.d[size_t(q)] = dq * dq + f[p];
  }
}

// One pass along `axis` over all lines of the box, in place on `dist`.
void transform_axis(std::vector<double>& dist, const std::array<int64_t, 3>& dims, int axis, double h, int threads) {
  const int64_t n = dims[size_t(axis)];
  const int64_t stride = axis == 0 ? 1 : (axis == 1 ? dims[0] : dims[0] * dims[1]);
  // Lines are indexed by the two other coordinates (a, b); `a` is the faster one.
  const int64_t na = axis == 0 ? dims[1] : dims[0];
  const int64_t nb = axis == 2 ? dims[1] : dims[2];
  const int64_t lines = na * nb;
  parallel_for(
      lines, threads,
      [&](int64_t first, int64_t last) {
        cpu_dispatch([&] {
          LineScratch s(n);
          for (int64_t l = first; l < last; ++l) {
            const int64_t a = l % na, b = l / na;
            int64_t base = 0;
            if (axis == 0) base = dims[0] * (a + dims[1] * b);
            if (axis == 1) base = a + dims[0] * dims[1] * b;
            if (axis == 2) base = a + dims[0] * b;
            double* line = dist.data() + base;
            for (int64_t q = 0; q < n; ++q) s.f[size_t(q)] = line[q * stride];
            transform_line(n, h, s);
            for (int64_t q = 0; q < n; ++q) line[q * stride] = s.d[size_t(q)];
          }
        });
      },
      64);
}

}  // namespace

Result<std::vector<double>> squared_distance_transform(const std::vector<uint8_t>& sources,
                                                       const std::array<int64_t, 3>& dims, const Vec3& spacing_mm,
                                                       int threads) {
  for (int a = 0; a < 3; ++a) {
    if (dims[size_t(a)] < 0) return invalid_argument("distance transform: box dimensions must be >= 0");
    if (!(spacing_mm[size_t(a)] > 0) || !std::isfinite(spacing_mm[size_t(a)])) {
      return invalid_argument("distance transform: spacing must be finite and > 0 mm, got " +
                              std::to_string(spacing_mm[size_t(a)]) + " along axis " + std::to_string(a));
    }
  }
  const int64_t count = dims[0] * dims[1] * dims[2];
  if (int64_t(sources.size()) != count) {
    return invalid_argument("distance transform: " + std::to_string(sources.size()) + " source flags for a box of " +
                            std::to_string(count) + " voxels");
  }
  std::vector<double> dist(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) dist[size_t(i)] = sources[size_t(i)] != 0 ? 0.0 : kInf;
  if (count == 0) return dist;
  for (int axis = 0; axis < 3; ++axis) transform_axis(dist, dims, axis, spacing_mm[size_t(axis)], threads);
  return dist;
}

}  // namespace soiq
