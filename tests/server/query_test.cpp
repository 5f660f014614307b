// The query's comparison on its own: each operator as written, and NaN (a value that could not be
// computed) matching no predicate, not even "not equal".
#include "server/app/query.h"

#include <gtest/gtest.h>

#include <cmath>

namespace soiq::server {
namespace {

TEST(Compare, EachOperatorComparesValueToThreshold) {
  EXPECT_TRUE(compare(1, Comparison::kLess, 2));
  EXPECT_FALSE(compare(2, Comparison::kLess, 2));
  EXPECT_TRUE(compare(2, Comparison::kLessOrEqual, 2));
  EXPECT_FALSE(compare(3, Comparison::kLessOrEqual, 2));
  EXPECT_TRUE(compare(3, Comparison::kGreater, 2));
  EXPECT_FALSE(compare(2, Comparison::kGreater, 2));
  EXPECT_TRUE(compare(2, Comparison::kGreaterOrEqual, 2));
  EXPECT_FALSE(compare(1, Comparison::kGreaterOrEqual, 2));
  EXPECT_TRUE(compare(2, Comparison::kEqual, 2));
  EXPECT_FALSE(compare(2, Comparison::kNotEqual, 2));
  EXPECT_TRUE(compare(1, Comparison::kNotEqual, 2));
}

TEST(Compare, NaNMatchesNoOperator) {
  for (Comparison op : {Comparison::kLess, Comparison::kLessOrEqual, Comparison::kGreater, Comparison::kGreaterOrEqual,
                        Comparison::kEqual, Comparison::kNotEqual})
    EXPECT_FALSE(compare(NAN, op, 0)) << int(op);
}

TEST(Compare, InfinitiesCompareAsNumbers) {
  EXPECT_TRUE(compare(INFINITY, Comparison::kGreater, 1e308));
  EXPECT_TRUE(compare(-INFINITY, Comparison::kLess, -1e308));
}

}  // namespace
}  // namespace soiq::server
