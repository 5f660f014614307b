#include "core/features/asymmetry_index.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace soiq {
namespace {

TEST(AsymmetryIndex, DifferenceOverTheMean) {
  auto a = asymmetry_index(3.0, 1.0);
  ASSERT_TRUE(a.ok());
  EXPECT_DOUBLE_EQ(*a, 1.0);  // (3 - 1) / 2
}

TEST(AsymmetryIndex, EqualSidesGiveZeroAndSwappingFlipsTheSign) {
  EXPECT_EQ(*asymmetry_index(4.5, 4.5), 0.0);
  EXPECT_DOUBLE_EQ(*asymmetry_index(2.0, 5.0), -*asymmetry_index(5.0, 2.0));
}

TEST(AsymmetryIndex, OneSideZeroGivesTwo) { EXPECT_DOUBLE_EQ(*asymmetry_index(7.0, 0.0), 2.0); }

TEST(AsymmetryIndex, ZeroSumIsInvalidArgument) {
  auto a = asymmetry_index(0.0, 0.0);
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(a.status().message().find("left + right = 0"), std::string::npos) << a.status().message();
}

TEST(AsymmetryIndex, NonFiniteInputIsInvalidArgument) {
  auto a = asymmetry_index(std::numeric_limits<double>::infinity(), 1.0);
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(a.status().message().find("finite"), std::string::npos) << a.status().message();
}

}  // namespace
}  // namespace soiq
