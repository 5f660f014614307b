#include "core/geometry/lattice_polygon.h"

#include <algorithm>
#include <cmath>

#include "core/base/cpu_dispatch.h"

namespace soiq {
namespace {

// Twice the signed area of (a, b, c): > 0 for a counter-clockwise turn. Exact below 2^62.
int64_t turn(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

}  // namespace

std::vector<LatticePoint> lattice_hull(const std::vector<LatticePoint>& points) {
  // Sorted by (u, v): each row's first and last points are its ends; a point between them lies
  // on the segment joining them, so it is never a vertex.
  std::vector<LatticeRow> rows;
  for (const LatticePoint& p : points) {
    if (rows.empty() || rows.back().u != p.u) {
      rows.push_back({p.u, p.v, p.v});
    } else {
      rows.back().hi = p.v;
    }
  }
  return lattice_hull_of_rows(rows);
}

static std::vector<LatticePoint> lattice_hull_of_rows_here(const std::vector<LatticeRow>& rows) {
  const size_t n = rows.size();
  if (n == 0) return {};
  const LatticePoint first{rows[0].u, rows[0].lo}, last{rows[n - 1].u, rows[n - 1].hi};
  if (n == 1)
    return rows[0].lo == rows[0].hi ? std::vector<LatticePoint>{first} : std::vector<LatticePoint>{first, last};
  std::vector<LatticePoint> hull(2 * n + 2);
  size_t h = 0;
  auto offer = [&](const LatticePoint& p, size_t keep) {
    while (h >= keep + 2 && turn(hull[h - 2], hull[h - 1], p) <= 0) --h;
    hull[h++] = p;
  };
  for (const LatticeRow& r : rows) offer({r.u, r.lo}, 0);  // lower chain
  if (last.v != rows[n - 1].lo) offer(last, 0);
  const size_t lower = h - 1;  // the upper chain may pop down to the lower chain's last point
  for (size_t k = n - 1; k-- > 0;) offer({rows[k].u, rows[k].hi}, lower);
  if (rows[0].hi != rows[0].lo) offer(first, lower);
  hull.resize(h - 1);  // the last point repeats the first
  return hull;
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
std::vector<LatticePoint> lattice_hull_of_rows(const std::vector<LatticeRow>& rows) {
  return cpu_dispatch([&] { return lattice_hull_of_rows_here(rows); });
}

namespace {

// The rotating calipers over the antipodal pairs of `hull`, measured by squared(a, b).
template <typename Squared>
double caliper_diameter(const std::vector<LatticePoint>& hull, Squared&& squared) {
  const size_t h = hull.size();
  if (h < 2) return 0;
  if (h == 2) return std::sqrt(squared(0, 1));
  double best = 0;
  size_t j = 1;
  for (size_t i = 0; i < h; ++i) {
    const size_t i1 = (i + 1) % h;
    // Advance j to the vertex farthest from edge (i, i1); the area grows, then falls (convexity).
    while (turn(hull[i], hull[i1], hull[(j + 1) % h]) > turn(hull[i], hull[i1], hull[j])) j = (j + 1) % h;
    best = std::max({best, squared(i, j), squared(i1, j)});
    // An edge parallel to (i, i1) at j: its other end is antipodal to both ends as well.
    const size_t j1 = (j + 1) % h;
    if (turn(hull[i], hull[i1], hull[j1]) == turn(hull[i], hull[i1], hull[j])) {
      best = std::max({best, squared(i, j1), squared(i1, j1)});
    }
  }
  return std::sqrt(best);
}

}  // namespace

double lattice_polygon_diameter(const std::vector<LatticePoint>& hull, double scale_u, double scale_v) {
  return caliper_diameter(hull, [&](size_t a, size_t b) {
    const double du = double(hull[a].u - hull[b].u) * scale_u, dv = double(hull[a].v - hull[b].v) * scale_v;
    return du * du + dv * dv;
  });
}

double lattice_polygon_diameter(const std::vector<LatticePoint>& hull, const Vec3& step_u, const Vec3& step_v) {
  return caliper_diameter(hull, [&](size_t a, size_t b) {
    const Vec3 d = double(hull[a].u - hull[b].u) * step_u + double(hull[a].v - hull[b].v) * step_v;
    return dot(d, d);
  });
}

}  // namespace soiq
