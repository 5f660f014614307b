#include "core/base/field_rules.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/base/utf8.h"

namespace soiq {
namespace {

// The value as a message may show it: 40 bytes at most, control bytes as '?'.
std::string quoted(std::string_view value) {
  std::string q(value.substr(0, 40));
  for (char& c : q) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return "'" + q + (value.size() > 40 ? "...'" : "'");
}

bool is_calendar_date(std::string_view s) {
  if (s.size() != 8) return false;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
  }
  const auto number = [&](size_t at, size_t n) {
    int v = 0;
    for (size_t i = at; i < at + n; ++i) v = v * 10 + (s[i] - '0');
    return v;
  };
  const std::chrono::year_month_day ymd{std::chrono::year{number(0, 4)}, std::chrono::month{unsigned(number(4, 2))},
                                        std::chrono::day{unsigned(number(6, 2))}};
  return number(0, 4) >= 1 && ymd.ok();
}

}  // namespace

Status check_date(std::string_view yyyymmdd) {
  if (yyyymmdd.empty() || is_calendar_date(yyyymmdd)) return ok_status();
  return invalid_argument(quoted(yyyymmdd) + " is not a calendar date YYYYMMDD");
}

Result<DateRange> parse_date_range(std::string_view text) {
  const size_t dash = text.find('-');
  DateRange r;
  if (dash == std::string_view::npos) {
    r.from = r.to = std::string(text);
  } else {
    r.from = std::string(text.substr(0, dash));
    r.to = std::string(text.substr(dash + 1));
  }
  const bool well_formed = !text.empty() && text != "-" &&
                           (dash == std::string_view::npos || text.find('-', dash + 1) == std::string_view::npos) &&
                           check_date(r.from).ok() && check_date(r.to).ok();
  if (!well_formed)
    return invalid_argument(quoted(text) + " is not a date or a date range (YYYYMMDD, YYYYMMDD-, -YYYYMMDD or " +
                            "YYYYMMDD-YYYYMMDD, calendar dates)");
  if (!r.from.empty() && !r.to.empty() && r.from > r.to)
    return invalid_argument("the date range " + quoted(text) + " ends before it starts");
  return r;
}

Status check_sex(std::string_view sex) {
  if (sex.empty() || sex == "M" || sex == "F" || sex == "O") return ok_status();
  return invalid_argument(quoted(sex) + " is not a sex: M, F or O");
}

Status check_laterality(std::string_view laterality) {
  if (laterality.empty() || laterality == "L" || laterality == "R") return ok_status();
  return invalid_argument(quoted(laterality) + " is not a laterality: L or R");
}

Status check_age_years(double years) {
  if (std::isfinite(years) && years >= 0 && years < 200) return ok_status();
  char text[40];
  std::snprintf(text, sizeof text, "%g", years);
  return invalid_argument(std::string(text) + " is not an age in years (at least 0, under 200)");
}

Status check_uid(std::string_view uid) {
  bool ok = uid.size() <= 64;
  for (const char c : uid) ok = ok && ((c >= '0' && c <= '9') || c == '.');
  if (ok) return ok_status();
  return invalid_argument(quoted(uid) + " is not a DICOM UID (at most 64 digits and dots)");
}

Status check_text(std::string_view text, size_t max_bytes, bool quote) {
  const std::string shown = quote ? quoted(text) + " " : "the value ";
  if (text.size() > max_bytes)
    return invalid_argument(shown + "is " + std::to_string(text.size()) + " bytes long; the limit is " +
                            std::to_string(max_bytes));
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return invalid_argument(shown + "contains a control character (newline, tab, ...)");
  }
  if (!is_utf8(text)) return invalid_argument(shown + "is not UTF-8 text");
  return ok_status();
}

Status check_id(std::string_view id) {
  if (id.empty()) return invalid_argument("is required");
  return check_text(id, kMaxIdBytes);
}

}  // namespace soiq
