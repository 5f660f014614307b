// Age at study from Patient's Age or from the birth and study dates, against hand counts.
#include "dicom/age_at_study.h"

#include <gtest/gtest.h>

namespace soiq::dicom {
namespace {

TEST(AgeAtStudy, PatientsAgeInEachUnit) {
  EXPECT_EQ(age_at_study("047Y", "", ""), 47.0);
  EXPECT_EQ(age_at_study("006M", "", ""), 0.5);
  EXPECT_DOUBLE_EQ(*age_at_study("052W", "", ""), 52 * 7 / 365.25);
  EXPECT_DOUBLE_EQ(*age_at_study("010D", "", ""), 10 / 365.25);
}

TEST(AgeAtStudy, PatientsAgeWinsOverTheDates) { EXPECT_EQ(age_at_study("061Y", "19000101", "20060128"), 61.0); }

TEST(AgeAtStudy, DatesGiveWholeYearsOnTheBirthday) {
  EXPECT_EQ(age_at_study("", "19691231", "20091231"), 40.0);
  // Half-way: 1 Jan 2001 -> 2 Jul 2001 is 182 of 365 days.
  EXPECT_DOUBLE_EQ(*age_at_study("", "20000101", "20010702"), 1 + 182.0 / 365.0);
}

TEST(AgeAtStudy, LeapDayBirthdayFallsOnTheTwentyEighthInCommonYears) {
  EXPECT_EQ(age_at_study("", "20000229", "20010228"), 1.0);
  EXPECT_EQ(age_at_study("", "20000229", "20040229"), 4.0);
}

TEST(AgeAtStudy, UnknownWhenNothingSaysOrTheStudyIsBeforeTheBirth) {
  EXPECT_FALSE(age_at_study("", "", "20060128").has_value());
  EXPECT_FALSE(age_at_study("", "19691231", "").has_value());
  EXPECT_FALSE(age_at_study("", "20100101", "20090101").has_value());
  EXPECT_FALSE(age_at_study("47Q", "", "").has_value());
  EXPECT_FALSE(age_at_study("", "20011341", "20060128").has_value());
}

}  // namespace
}  // namespace soiq::dicom
