// Eigenvalues of symmetric 3x3 matrices against matrices built from known eigenvalues.
#include "core/geometry/symmetric_eigenvalues.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace soiq {
namespace {

// R diag(l) R^T for the rotation R about the unit axis `u` by `angle`.
Mat3 rotated_diagonal(const Vec3& l, Vec3 u, double angle) {
  u = (1 / norm(u)) * u;
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i][j] = (i == j ? c : 0) + (1 - c) * u[i] * u[j];
  }
  r[0][1] -= s * u[2], r[0][2] += s * u[1], r[1][0] += s * u[2];
  r[1][2] -= s * u[0], r[2][0] -= s * u[1], r[2][1] += s * u[0];
  Mat3 m{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) m[i][j] += r[i][k] * l[k] * r[j][k];
    }
  }
  return m;
}

TEST(SymmetricEigenvalues, DiagonalMatrixGivesItsDiagonalSortedDescending) {
  const Vec3 l = symmetric_eigenvalues({{{1, 0, 0}, {0, 7, 0}, {0, 0, 3}}});
  EXPECT_EQ(l, (Vec3{7, 3, 1}));
}

TEST(SymmetricEigenvalues, ZeroMatrixGivesZeros) { EXPECT_EQ(symmetric_eigenvalues(Mat3{}), (Vec3{0, 0, 0})); }

TEST(SymmetricEigenvalues, HandComputedCoupledPair) {
  // [[2,1],[1,2]] has eigenvalues 3 and 1; the third axis is decoupled with 0.
  const Vec3 l = symmetric_eigenvalues({{{2, 1, 0}, {1, 2, 0}, {0, 0, 0}}});
  EXPECT_NEAR(l[0], 3, 1e-15);
  EXPECT_NEAR(l[1], 1, 1e-15);
  EXPECT_NEAR(l[2], 0, 1e-15);
}

TEST(SymmetricEigenvalues, RandomRotationsOfKnownSpectraAreRecovered) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    Vec3 l{std::fabs(unit(rng)) * 100, std::fabs(unit(rng)) * 10, std::fabs(unit(rng))};
    if (trial % 3 == 0) l[1] = l[0];  // repeated eigenvalues
    if (trial % 5 == 0) l[2] = 0;     // a flat structure
    const Mat3 m = rotated_diagonal(l, {unit(rng), unit(rng), unit(rng) + 2}, unit(rng) * 3.14159);
    Vec3 expected = l;
    std::sort(expected.begin(), expected.end(), std::greater<double>());
    const Vec3 got = symmetric_eigenvalues(m);
    // Backward stable: errors of a few ulps of the largest eigenvalue (plus those of building m).
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[a], expected[a], 1e-13 * expected[0]) << "trial " << trial;
  }
}

TEST(SymmetricEigenvalues, ReadsOnlyTheUpperTriangle) {
  const Vec3 l = symmetric_eigenvalues({{{2, 1, 0}, {99, 2, 0}, {99, 99, 0}}});
  EXPECT_NEAR(l[0], 3, 1e-15);
  EXPECT_NEAR(l[1], 1, 1e-15);
}

}  // namespace
}  // namespace soiq
