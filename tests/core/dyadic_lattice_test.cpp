// dyadic_lattice_exponent against hand-made sets: the exponent is the least that makes every
// coordinate an integer, and sets beyond 2^15 after scaling, or off every dyadic lattice, are not
// lattices.
#include "core/geometry/dyadic_lattice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace soiq {
namespace {

TEST(DyadicLattice, ExponentIsTheLeastThatMakesEveryCoordinateAnInteger) {
  EXPECT_EQ(dyadic_lattice_exponent({{0, 1, -2}, {3, 4, 5}}), 0);
  EXPECT_EQ(dyadic_lattice_exponent({{0.5, 1, -2}, {3, 4, 5}}), 1);
  EXPECT_EQ(dyadic_lattice_exponent({{0.5, -0.125, 2}, {0.25, 0, -0.0}}), 3);
  EXPECT_EQ(dyadic_lattice_exponent({{-24.51171875, 0.9765625, 0}}), 8);       // CT-like origin and spacing
  EXPECT_FALSE(dyadic_lattice_exponent({{-249.51171875, 0, 0}}).has_value());  // 2^8 * 249.5... > 2^15
  EXPECT_EQ(dyadic_lattice_exponent({}), 0);
}

TEST(DyadicLattice, LargeOrNonDyadicOrNonFiniteSetsAreNot) {
  EXPECT_EQ(dyadic_lattice_exponent({{32767, 0, 0}}), 0);
  EXPECT_FALSE(dyadic_lattice_exponent({{32768, 0, 0}}).has_value());
  EXPECT_FALSE(dyadic_lattice_exponent({{16383.75, 0, 0}}).has_value());  // 2^2 * 16383.75 >= 2^15
  EXPECT_FALSE(dyadic_lattice_exponent({{0.1, 0, 0}}).has_value());
  EXPECT_FALSE(dyadic_lattice_exponent({{std::ldexp(1.0, -70), 0, 0}}).has_value());  // more than 64 bits
  EXPECT_FALSE(dyadic_lattice_exponent({{std::numeric_limits<double>::denorm_min(), 0, 0}}).has_value());
  EXPECT_FALSE(dyadic_lattice_exponent({{NAN, 0, 0}}).has_value());
  EXPECT_FALSE(dyadic_lattice_exponent({{0, -INFINITY, 0}}).has_value());
}

}  // namespace
}  // namespace soiq
