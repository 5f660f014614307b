// The one rule of each field (core/base/field_rules.h), and Status::in_field, which every layer uses
// to name the field a rule's error is about. Dates are checked against std::chrono's calendar on
// every day of 400 years (a whole Gregorian cycle) and a hand list of the edges.
#include "core/base/field_rules.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace soiq {
namespace {

TEST(CheckDate, EveryDayOfAGregorianCycleAndNothingElse) {
  using namespace std::chrono;
  int count = 0;
  for (sys_days d = sys_days{year{2000} / January / 1}; d < sys_days{year{2400} / January / 1}; d += days{1}) {
    const year_month_day ymd{d};
    char text[16];
    std::snprintf(text, sizeof text, "%04d%02u%02u", int(ymd.year()), unsigned(ymd.month()), unsigned(ymd.day()));
    ASSERT_TRUE(check_date(text).ok()) << text;
    ++count;
  }
  EXPECT_EQ(count, 146097);  // 400 Gregorian years
  // Every day number 29..31 of every month of a leap and a common year, against the calendar.
  for (const int y : {2023, 2024}) {
    for (unsigned m = 1; m <= 12; ++m) {
      for (unsigned d = 29; d <= 32; ++d) {
        char text[16];
        std::snprintf(text, sizeof text, "%04d%02u%02u", y, m, d);
        EXPECT_EQ(check_date(text).ok(), (year{y} / month{m} / day{d}).ok()) << text;
      }
    }
  }
}

TEST(CheckDate, RefusesWhatIsNotYYYYMMDDSayingWhy) {
  EXPECT_TRUE(check_date("").ok());  // unknown
  for (const char* bad : {"20230231", "19001301", "00000101", "2024-01-01", "2024011", "202401011", "2024O101",
                          " 20240101", "20240100"}) {
    const Status s = check_date(bad);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_EQ(s.message(), "'" + std::string(bad) + "' is not a calendar date YYYYMMDD");
  }
  EXPECT_TRUE(check_date("99991231").ok());
  EXPECT_TRUE(check_date("00010101").ok());
}

TEST(ParseDateRange, TheFourFormsAndTheirRefusals) {
  const auto range = [](const char* t) {
    const Result<DateRange> r = parse_date_range(t);
    return r.ok() ? r->from + "|" + r->to : "error: " + r.status().message();
  };
  EXPECT_EQ(range("20240229"), "20240229|20240229");
  EXPECT_EQ(range("20240101-"), "20240101|");
  EXPECT_EQ(range("-20240101"), "|20240101");
  EXPECT_EQ(range("20200101-20240101"), "20200101|20240101");
  EXPECT_EQ(range("20240101-20200101"), "error: the date range '20240101-20200101' ends before it starts");
  for (const char* bad : {"", "-", "20230229", "2020-01-01", "20200101-20210101-", "20200101--20210101"})
    EXPECT_NE(range(bad).find("is not a date or a date range"), std::string::npos) << bad << ": " << range(bad);
}

TEST(FieldRules, SexLateralityAgesAndUids) {
  for (const char* ok : {"", "M", "F", "O"}) EXPECT_TRUE(check_sex(ok).ok()) << ok;
  for (const char* bad : {"m", "X", "MF", "male"}) EXPECT_FALSE(check_sex(bad).ok()) << bad;
  for (const char* ok : {"", "L", "R"}) EXPECT_TRUE(check_laterality(ok).ok()) << ok;
  for (const char* bad : {"l", "left", "B"}) EXPECT_FALSE(check_laterality(bad).ok()) << bad;
  for (const double ok : {0.0, 0.5, 42.0, 199.99}) EXPECT_TRUE(check_age_years(ok).ok()) << ok;
  for (const double bad : {-0.001, 200.0, 1e9, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_FALSE(check_age_years(bad).ok()) << bad;
  EXPECT_TRUE(check_uid("").ok());
  EXPECT_TRUE(check_uid("1.2.840.10008.5.1.4.1.1.2").ok());
  EXPECT_FALSE(check_uid("1.2.a").ok());
  EXPECT_FALSE(check_uid(std::string(65, '1')).ok());
  EXPECT_TRUE(check_uid(std::string(64, '1')).ok());
}

TEST(CheckText, UTF8WithoutControlCharactersWithinItsLength) {
  EXPECT_TRUE(check_text("Müller^Jürgen 山田", kMaxNameBytes).ok());
  EXPECT_EQ(check_text("a\nb", kMaxIdBytes).message(), "'a?b' contains a control character (newline, tab, ...)");
  EXPECT_EQ(check_text("M\xfcller", kMaxIdBytes).message(), "'M\xfcller' is not UTF-8 text");  // Latin-1
  EXPECT_EQ(check_text(std::string(65, 'x'), kMaxIdBytes).message().find("is 65 bytes long; the limit is 64") !=
                std::string::npos,
            true);
  // A value that must not reach a log is described, not shown.
  EXPECT_EQ(check_text("Doe\x01", kMaxNameBytes, false).message(),
            "the value contains a control character (newline, tab, ...)");
  EXPECT_EQ(check_id("").message(), "is required");
  EXPECT_TRUE(check_id("STS_002").ok());
}

TEST(StatusInField, NamesTheFieldInFrontAndKeepsBothApart) {
  const Status s = invalid_argument("'X' is not a sex: M, F or O").in_field("patient.sex");
  EXPECT_EQ(s.message(), "patient.sex: 'X' is not a sex: M, F or O");
  EXPECT_EQ(s.field(), "patient.sex");
  EXPECT_EQ(s.reason(), "'X' is not a sex: M, F or O");
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  // Nested: an index keeps no dot, a name gets one.
  const Status nested = invalid_argument("unknown").in_field("feature").in_field("where[2]");
  EXPECT_EQ(nested.field(), "where[2].feature");
  EXPECT_EQ(nested.message(), "where[2].feature: unknown");
  EXPECT_EQ(nested.reason(), "unknown");
  EXPECT_EQ(invalid_argument("x").in_field("[3]").in_field("where").field(), "where[3]");
  // OK stays OK, and no field leaves the status as it was.
  EXPECT_TRUE(ok_status().in_field("a").ok());
  EXPECT_EQ(invalid_argument("plain").in_field("").field(), "");
  EXPECT_EQ(invalid_argument("plain").reason(), "plain");
}

}  // namespace
}  // namespace soiq
