#include "db/age_years.h"

#include <chrono>

#include "core/base/field_rules.h"
#include "db/record_merge.h"

namespace soiq::db {
namespace {

using std::chrono::day;
using std::chrono::month;
using std::chrono::sys_days;
using std::chrono::year;
using std::chrono::year_month_day;

std::optional<year_month_day> parse_date(const std::string& s) {
  if (s.size() != 8) return std::nullopt;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  const int y = std::stoi(s.substr(0, 4));
  const unsigned m = unsigned(std::stoi(s.substr(4, 2)));
  const unsigned d = unsigned(std::stoi(s.substr(6, 2)));
  const year_month_day ymd{year{y}, month{m}, day{d}};
  if (y < 1 || !ymd.ok()) return std::nullopt;
  return ymd;
}

// The `n`-th anniversary of `birth`; 29 February falls back to 28 February in common years.
sys_days anniversary(const year_month_day& birth, int n) {
  year_month_day a{birth.year() + std::chrono::years{n}, birth.month(), birth.day()};
  if (!a.ok()) a = year_month_day{a.year(), a.month(), day{28}};
  return sys_days{a};
}

}  // namespace

Result<std::optional<double>> age_years(const std::string& birth_date, const std::string& study_date) {
  SOIQ_RETURN_IF_ERROR(check_date(birth_date).in_field("birth date"));
  SOIQ_RETURN_IF_ERROR(check_date(study_date).in_field("study date"));
  if (birth_date.empty() || study_date.empty()) return std::optional<double>();
  const year_month_day birth = *parse_date(birth_date);
  const sys_days study{*parse_date(study_date)};
  if (study < sys_days{birth}) return std::optional<double>();
  int years = int(year_month_day{study}.year()) - int(birth.year());
  // The estimate may be one too many (birthday not reached yet this year).
  if (anniversary(birth, years) > study) --years;
  const sys_days last = anniversary(birth, years);
  const sys_days next = anniversary(birth, years + 1);
  const double fraction = double((study - last).count()) / double((next - last).count());
  return std::optional<double>(years + fraction);
}

Result<std::optional<double>> study_age(const std::optional<double>& given, const std::optional<double>& stored_given,
                                        const std::string& birth_date, const std::string& study_date) {
  if (given) return given;
  if (stored_given) return stored_given;
  return age_years(birth_date, study_date);
}

}  // namespace soiq::db
