#include "dicom/pet_suv.h"

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>

namespace soiq::dicom {
namespace {

// Seconds since midnight of "HHMMSS(.ffffff)" (also "HH", "HHMM"); nullopt when malformed.
std::optional<double> parse_time(const std::string& tm) {
  if (tm.size() < 2) return std::nullopt;
  for (size_t i = 0; i < std::min<size_t>(tm.size(), 6); ++i)
    if (!std::isdigit(static_cast<unsigned char>(tm[i]))) return std::nullopt;
  const auto field = [&](size_t at) { return tm.size() >= at + 2 ? std::atoi(tm.substr(at, 2).c_str()) : 0; };
  double s = field(0) * 3600.0 + field(2) * 60.0 + field(4);
  if (tm.size() > 6 && tm[6] == '.') s += std::atof(tm.substr(6).c_str());
  return s;
}

// Seconds since 1970-01-01 of "YYYYMMDD" plus a time of day; nullopt when malformed.
std::optional<double> parse_date_time(const std::string& da, const std::string& tm) {
  if (da.size() != 8) return std::nullopt;
  for (char c : da)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  const std::chrono::year_month_day d{std::chrono::year{std::atoi(da.substr(0, 4).c_str())},
                                      std::chrono::month{static_cast<unsigned>(std::atoi(da.substr(4, 2).c_str()))},
                                      std::chrono::day{static_cast<unsigned>(std::atoi(da.substr(6, 2).c_str()))}};
  const auto t = parse_time(tm);
  if (!d.ok() || !t) return std::nullopt;
  return std::chrono::sys_days{d}.time_since_epoch().count() * 86400.0 + *t;
}

}  // namespace

SuvScale suv_body_weight(const PetTags& t) {
  SuvScale out;
  out.units = t.units;
  if (t.units == "GML") {
    out.units = "SUVbw";
    return out;
  }
  std::string missing;
  const auto need = [&](bool ok, const char* what) {
    if (!ok) missing += missing.empty() ? what : std::string(", ") + what;
  };
  need(t.units == "BQML", "Units BQML");
  need(t.decay_correction == "START", "Decay Correction START");
  need(t.patient_weight_kg && *t.patient_weight_kg > 0, "Patient's Weight");
  need(t.total_dose_bq && *t.total_dose_bq > 0, "Radionuclide Total Dose");
  need(t.half_life_s && *t.half_life_s > 0, "Radionuclide Half Life");

  // Elapsed time from injection to the scan start: with dates when both sides have them.
  std::optional<double> elapsed;
  if (t.injection_datetime.size() >= 14) {
    const auto t0 = parse_date_time(t.injection_datetime.substr(0, 8), t.injection_datetime.substr(8));
    const auto t1 = parse_date_time(t.series_date, t.series_time);
    if (t0 && t1 && *t1 >= *t0) elapsed = *t1 - *t0;  // else: de-identified dates shifted apart
  }
  if (!elapsed) {
    const auto t0 = parse_time(t.injection_time);
    const auto t1 = parse_time(t.series_time);
    if (t0 && t1) elapsed = *t1 >= *t0 ? *t1 - *t0 : *t1 + 86400.0 - *t0;
  }
  need(elapsed && *elapsed >= 0, "Radiopharmaceutical Start Time before the Series Time");
  if (!missing.empty()) {
    out.note = "values kept in the stored units ('" + t.units + "'); SUV needs " + missing;
    return out;
  }
  const double dose_at_scan = *t.total_dose_bq * std::exp2(-*elapsed / *t.half_life_s);
  out.factor = *t.patient_weight_kg * 1000.0 / dose_at_scan;
  out.units = "SUVbw";
  return out;
}

}  // namespace soiq::dicom
