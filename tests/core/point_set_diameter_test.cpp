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

TEST(PointSetDiameter, EqualsAllPairsWhereTheDistanceFilterDropsMostPoints) {
  // Elongated clouds (the filter keeps their two ends), thin shells (it keeps the outer layer) and
  // a cloud with one far outlier (it keeps the outlier and the far side): the filter by distance
  // from the box centre must never drop a point of the longest pair.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  for (int trial = 0; trial < 30; ++trial) {
    const size_t n = size_t(50 + trial * 61);
    std::vector<Vec3> p(n);
    for (auto& q : p) {
      q = {g(rng), g(rng), g(rng)};
      if (trial % 3 == 0) q[0] *= 12;  // a cigar
      if (trial % 3 == 1) {            // a shell of radius 50, jittered
        q = (50 / norm(q)) * q;
        for (double& x : q) x += jitter(rng);
      }
    }
    if (trial % 3 == 2) p[n / 2] = {40, -3, 7};            // one outlier
    for (auto& q : p) q = q + Vec3{-120.5, 310.25, 1002};  // patient coordinates, far from 0
    EXPECT_EQ(point_set_diameter(p), all_pairs(p)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace soiq
