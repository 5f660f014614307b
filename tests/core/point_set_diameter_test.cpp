// The branch-and-bound diameter against the all-pairs loop it replaces.
#include "core/geometry/point_set_diameter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace soiq {
namespace {

double all_pairs(const std::vector<Vec3>& p) {
  double best = 0;
  for (size_t a = 0; a < p.size(); ++a) {
    for (size_t b = a + 1; b < p.size(); ++b) {
      const Vec3 d = p[a] - p[b];
      best = std::max(best, dot(d, d));
    }
  }
  return std::sqrt(best);
}

TEST(PointSetDiameter, FewerThanTwoPointsHaveDiameterZero) {
  EXPECT_EQ(point_set_diameter({}), 0);
  EXPECT_EQ(point_set_diameter({{1, 2, 3}}), 0);
}

TEST(PointSetDiameter, TwoPointsAreTheirDistance) { EXPECT_EQ(point_set_diameter({{0, 0, 0}, {3, 4, 12}}), 13); }

TEST(PointSetDiameter, EqualsAllPairsOnRandomSets) {
  // Clouds, sphere surfaces (no pruning by position alone), flat sets and many duplicates.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const size_t n = size_t(2 + trial * 37);
    std::vector<Vec3> p(n);
    for (auto& q : p) {
      q = {g(rng), g(rng), g(rng)};
      if (trial % 4 == 1) q = (1 / norm(q)) * q;                          // on the unit sphere
      if (trial % 4 == 2) q[2] = 0;                                       // coplanar
      if (trial % 4 == 3) q = {std::round(q[0]), std::round(q[1]), 0.5};  // duplicates, ties
    }
    EXPECT_EQ(point_set_diameter(p), all_pairs(p)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace soiq
