#include "db/age_years.h"

#include <gtest/gtest.h>

namespace soiq::db {
namespace {

double age(const std::string& birth, const std::string& study) {
  auto a = age_years(birth, study);
  EXPECT_TRUE(a.ok()) << a.status().to_string();
  EXPECT_TRUE(a->has_value());
  return a->value_or(-1);
}

TEST(AgeYears, IsAnExactIntegerOnEachBirthday) {
  EXPECT_EQ(age("19500315", "20150315"), 65.0);
  EXPECT_EQ(age("19500315", "19500315"), 0.0);
}

TEST(AgeYears, DayBeforeTheBirthdayIsStillTheYoungerAge) {
  const double a = age("19500315", "20150314");
  EXPECT_LT(a, 65.0);
  EXPECT_GT(a, 64.99);
}

TEST(AgeYears, FractionIsDaysSinceBirthdayOverDaysInThatYearOfLife) {
  // 2015-03-15 to 2016-03-15 spans 366 days (29 Feb 2016); 2015-09-15 is 184 days in.
  EXPECT_DOUBLE_EQ(age("19500315", "20150915"), 65.0 + 184.0 / 366.0);
}

TEST(AgeYears, LeapDayBirthdayFallsOnFebruary28InCommonYears) {
  EXPECT_EQ(age("20000229", "20010228"), 1.0);
  EXPECT_EQ(age("20000229", "20040229"), 4.0);
  EXPECT_LT(age("20000229", "20010227"), 1.0);
}

TEST(AgeYears, UnknownWhenADateIsMissingOrTheStudyPrecedesTheBirth) {
  EXPECT_FALSE(age_years("", "20200101")->has_value());
  EXPECT_FALSE(age_years("20000101", "")->has_value());
  EXPECT_FALSE(age_years("20000102", "20000101")->has_value());
}

TEST(AgeYears, MalformedDateIsInvalidArgumentNamingIt) {
  for (const std::string bad : {"2020-01-01", "20200230", "20201301", "2020011", "abcdefgh", "00000101"}) {
    auto a = age_years(bad, "20200101");
    ASSERT_FALSE(a.ok()) << bad;
    EXPECT_EQ(a.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(a.status().message().find(bad), std::string::npos) << a.status().message();
  }
}

}  // namespace
}  // namespace soiq::db
