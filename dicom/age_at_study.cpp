#include "dicom/age_at_study.h"

#include <cctype>
#include <chrono>

namespace soiq::dicom {
namespace {

std::optional<std::chrono::year_month_day> parse_date(const std::string& s) {
  if (s.size() != 8) return std::nullopt;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  const std::chrono::year_month_day d{std::chrono::year{std::stoi(s.substr(0, 4))},
                                      std::chrono::month{static_cast<unsigned>(std::stoi(s.substr(4, 2)))},
                                      std::chrono::day{static_cast<unsigned>(std::stoi(s.substr(6, 2)))}};
  if (!d.ok()) return std::nullopt;
  return d;
}

// The birthday in year `y`; 29 February becomes 28 February in common years.
std::chrono::sys_days anniversary(const std::chrono::year_month_day& birth, std::chrono::year y) {
  std::chrono::year_month_day d{y, birth.month(), birth.day()};
  if (!d.ok()) d = std::chrono::year_month_day{y, birth.month(), std::chrono::day{28}};
  return std::chrono::sys_days{d};
}

}  // namespace

std::optional<double> parse_patient_age(const std::string& patient_age) {
  if (patient_age.size() < 2 || patient_age.size() > 4) return std::nullopt;
  const std::string digits = patient_age.substr(0, patient_age.size() - 1);
  for (char c : digits)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  const double n = std::stod(digits);
  switch (patient_age.back()) {
    case 'Y':
      return n;
    case 'M':
      return n / 12.0;
    case 'W':
      return n * 7.0 / 365.25;
    case 'D':
      return n / 365.25;
    default:
      return std::nullopt;
  }
}

std::optional<double> age_at_study(const std::string& patient_age, const std::string& birth_date,
                                   const std::string& study_date) {
  if (const auto given = parse_patient_age(patient_age)) return given;
  const auto birth = parse_date(birth_date);
  const auto study = parse_date(study_date);
  if (!birth || !study) return std::nullopt;
  const std::chrono::sys_days s{*study};
  if (s < std::chrono::sys_days{*birth}) return std::nullopt;
  std::chrono::year y = study->year();
  if (anniversary(*birth, y) > s) --y;
  const auto last = anniversary(*birth, y);
  const auto next = anniversary(*birth, y + std::chrono::years{1});
  const int completed = static_cast<int>(y) - static_cast<int>(birth->year());
  return completed + static_cast<double>((s - last).count()) / static_cast<double>((next - last).count());
}

}  // namespace soiq::dicom
