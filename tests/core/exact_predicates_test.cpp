// The exact predicates against integer arithmetic: inputs are integers (exact in double), chosen so
// the double evaluation alone would often get the sign wrong; __int128 gives the true sign.
#include "core/geometry/exact_predicates.h"

#include <gtest/gtest.h>

#include <random>

namespace soiq {
namespace {

int sign128(__int128 v) { return (v > 0) - (v < 0); }

TEST(ExactPredicates, Orient2dSignMatchesIntegerArithmeticOnNearCollinearPoints) {
  std::mt19937_64 rng(7);
  // Coordinates below 2^53 (exact in double) whose products need ~100 bits.
  std::uniform_int_distribution<int64_t> coord(-(int64_t(1) << 48), int64_t(1) << 48);
  std::uniform_int_distribution<int64_t> nudge(-1, 1);
  int wrong_in_double = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int64_t a1 = coord(rng), a2 = coord(rng);
    const int64_t d1 = coord(rng) / 4, d2 = coord(rng) / 4;
    const int64_t t = int64_t(rng() % 128) - 64;
    // p is on the line a + t * d, nudged by at most 2 units: the determinant is tiny or zero.
    const int64_t p1 = a1 + t * d1 + nudge(rng), p2 = a2 + t * d2 + nudge(rng);
    const int64_t b1 = a1 + d1, b2 = a2 + d2;
    const __int128 exact = __int128(b1 - a1) * (p2 - a2) - __int128(b2 - a2) * (p1 - a1);
    const double naive =
        (double(b1) - double(a1)) * (double(p2) - double(a2)) - (double(b2) - double(a2)) * (double(p1) - double(a1));
    wrong_in_double += ((naive > 0) - (naive < 0)) != sign128(exact);
    ASSERT_EQ(orient2d_sign(double(a1), double(a2), double(b1), double(b2), double(p1), double(p2)), sign128(exact))
        << "trial " << trial;
  }
  // The test is only worth something if plain double evaluation fails on it.
  EXPECT_GT(wrong_in_double, 20);
}

TEST(ExactPredicates, Orient3dSignMatchesIntegerArithmeticOnNearCoplanarPoints) {
  std::mt19937_64 rng(11);
  // u and v nearly parallel and d near their plane: the determinant is tiny against its terms.
  std::uniform_int_distribution<int64_t> coord(-(int64_t(1) << 44), int64_t(1) << 44);
  std::uniform_int_distribution<int64_t> small(-8, 8);
  std::uniform_int_distribution<int64_t> nudge(-1, 1);
  int wrong_in_double = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    int64_t a[3], u[3], v[3], d[3];
    const int64_t s = small(rng), t = small(rng);
    for (int c = 0; c < 3; ++c) {
      a[c] = coord(rng);
      u[c] = coord(rng) >> 8;
      v[c] = 3 * u[c] + small(rng);
      d[c] = a[c] + s * u[c] + t * v[c] + nudge(rng);
    }
    const int64_t b[3] = {a[0] + u[0], a[1] + u[1], a[2] + u[2]};
    const int64_t c3[3] = {a[0] + v[0], a[1] + v[1], a[2] + v[2]};
    const __int128 w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    const __int128 exact = __int128(u[0]) * (__int128(v[1]) * w[2] - __int128(v[2]) * w[1]) +
                           __int128(u[1]) * (__int128(v[2]) * w[0] - __int128(v[0]) * w[2]) +
                           __int128(u[2]) * (__int128(v[0]) * w[1] - __int128(v[1]) * w[0]);
    const double da[3] = {double(a[0]), double(a[1]), double(a[2])};
    const double db[3] = {double(b[0]), double(b[1]), double(b[2])};
    const double dc[3] = {double(c3[0]), double(c3[1]), double(c3[2])};
    const double dd[3] = {double(d[0]), double(d[1]), double(d[2])};
    const double du[3] = {db[0] - da[0], db[1] - da[1], db[2] - da[2]};
    const double dv[3] = {dc[0] - da[0], dc[1] - da[1], dc[2] - da[2]};
    const double dw[3] = {dd[0] - da[0], dd[1] - da[1], dd[2] - da[2]};
    const double naive = du[0] * (dv[1] * dw[2] - dv[2] * dw[1]) + du[1] * (dv[2] * dw[0] - dv[0] * dw[2]) +
                         du[2] * (dv[0] * dw[1] - dv[1] * dw[0]);
    wrong_in_double += ((naive > 0) - (naive < 0)) != sign128(exact);
    ASSERT_EQ(orient3d_sign(da, db, dc, dd), sign128(exact)) << "trial " << trial;
  }
  EXPECT_GT(wrong_in_double, 20);
}

TEST(ExactPredicates, ExactZeroIsZero) {
  EXPECT_EQ(orient2d_sign(0.1, 0.2, 0.1, 0.2, 5, 7), 0);  // a == b
  EXPECT_EQ(orient2d_sign(1, 1, 3, 3, 2, 2), 0);
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0.3, 0.7, 0};
  EXPECT_EQ(orient3d_sign(a, b, c, d), 0);
}

}  // namespace
}  // namespace soiq
