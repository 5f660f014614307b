// The exact lattice hull and the calipers diameter against brute force on random point sets.
#include "core/geometry/lattice_polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace soiq {
namespace {

std::vector<LatticePoint> sorted_unique(std::vector<LatticePoint> p) {
  std::sort(p.begin(), p.end(),
            [](const LatticePoint& a, const LatticePoint& b) { return a.u != b.u ? a.u < b.u : a.v < b.v; });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

// A point is a hull vertex iff some direction has it as the unique maximiser; brute force over
// the points: it is not one iff it lies in a triangle of others or on a segment between two.
TEST(LatticePolygon, DiameterEqualsAllPairsOnRandomSets) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 3000; ++trial) {
    const int range = 1 + trial % 12;  // small ranges: many collinear and parallel edges
    std::uniform_int_distribution<int64_t> coord(-range, range);
    std::uniform_int_distribution<int> count(1, 40);
    std::vector<LatticePoint> raw(size_t(count(rng)));
    for (auto& p : raw) p = {coord(rng), coord(rng)};
    const auto points = sorted_unique(raw);
    const double su = trial % 3 == 0 ? 1.0 : 0.5 + 0.37 * (trial % 5),
                 sv = trial % 3 == 0 ? 1.0 : 0.25 + 0.9 * (trial % 4);
    double brute = 0;
    for (const auto& a : points) {
      for (const auto& b : points) {
        const double du = double(a.u - b.u) * su, dv = double(a.v - b.v) * sv;
        brute = std::max(brute, du * du + dv * dv);
      }
    }
    const auto hull = lattice_hull(points);
    EXPECT_EQ(lattice_polygon_diameter(hull, su, sv), std::sqrt(brute)) << "trial " << trial;
    // Every input point is inside or on the counter-clockwise hull; hull turns are strict.
    for (size_t i = 0; hull.size() >= 3 && i < hull.size(); ++i) {
      const auto& a = hull[i];
      const auto& b = hull[(i + 1) % hull.size()];
      const auto& c = hull[(i + 2) % hull.size()];
      EXPECT_GT((b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u), 0);
      for (const auto& p : points) EXPECT_GE((b.u - a.u) * (p.v - a.v) - (b.v - a.v) * (p.u - a.u), 0);
    }
  }
}

TEST(LatticePolygon, HullOfRowsEqualsHullOfTheirPoints) {
  std::mt19937_64 rng(12);
  for (int trial = 0; trial < 5000; ++trial) {
    const int range = 1 + trial % 9;  // small ranges: collinear ends, single-point rows, vertical edges
    std::uniform_int_distribution<int64_t> value(-range, range);
    std::vector<LatticeRow> rows;
    std::vector<LatticePoint> points;
    for (int64_t u = -3 + trial % 4; u < 1 + int64_t(trial % 7); ++u) {
      if (rng() % 4 == 0) continue;  // a row without points
      int64_t lo = value(rng), hi = value(rng);
      if (lo > hi) std::swap(lo, hi);
      if (rng() % 3 == 0) hi = lo;
      rows.push_back({u, lo, hi});
      points.push_back({u, lo});
      if (hi != lo) points.push_back({u, hi});
    }
    EXPECT_EQ(lattice_hull_of_rows(rows), lattice_hull(points)) << "trial " << trial;
  }
  EXPECT_TRUE(lattice_hull_of_rows({}).empty());
}

TEST(LatticePolygon, CollinearPointsGiveTheirEnds) {
  const auto hull = lattice_hull({{0, 0}, {1, 1}, {2, 2}, {3, 3}});
  ASSERT_EQ(hull.size(), 2u);
  EXPECT_EQ(hull[0], (LatticePoint{0, 0}));
  EXPECT_EQ(hull[1], (LatticePoint{3, 3}));
  EXPECT_DOUBLE_EQ(lattice_polygon_diameter(hull, 1, 2), std::sqrt(9.0 + 36.0));
}

}  // namespace
}  // namespace soiq
