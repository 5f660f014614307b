#pragma once
// The one rule of each field a record or a filter carries, whichever door it comes through: the
// command line (client/cli), the API (server/api), the DICOM import, QIDO and PACS queries, and the
// store (db/validate_records.cpp) all call these, so a value is refused the same way and in the same
// words everywhere, and both store backends hold the same values (PostgreSQL's text must be UTF-8,
// so every text is UTF-8 everywhere).
//
// Input    the value as text (the field's name is the caller's: Status::in_field adds it).
// Output   OK, or INVALID_ARGUMENT with the reason alone ("'20230231' is not a calendar date
//          YYYYMMDD"), quoting at most 40 bytes of the value with control bytes shown as '?'.
// Cost     O(length); pure and thread-safe.

#include <cstddef>
#include <string>
#include <string_view>

#include "core/base/status.h"

namespace soiq {

// Lengths a client may name, in bytes: identifiers as DICOM bounds them (LO and UI are 64
// characters), names, descriptions and globs generously above any DICOM value, so that a 1 MB
// "name" is refused rather than stored, logged and echoed.
inline constexpr size_t kMaxIdBytes = 64;
inline constexpr size_t kMaxNameBytes = 256;

// "" (unknown) or a calendar date YYYYMMDD of the years 0001..9999 (DICOM DA): 20240229 is one,
// 20230229 and 20230431 are not.
Status check_date(std::string_view yyyymmdd);

// A DICOM date range (PS3.4 C.2.2.2.5): "D" (that day), "D-" (from), "-D" (to) or "D1-D2" with
// D1 <= D2; each D as check_date. The bounds are inclusive; "" for an open end.
struct DateRange {
  std::string from, to;
};
Result<DateRange> parse_date_range(std::string_view text);

// "" or one of M, F, O (DICOM's Patient's Sex).
Status check_sex(std::string_view sex);
// "" or one of L, R.
Status check_laterality(std::string_view laterality);
// An age in years, at a study or as a query's bound: finite, >= 0 and < 200.
Status check_age_years(double years);
// "" or a DICOM UID: at most 64 characters, digits and '.' only.
Status check_uid(std::string_view uid);
// Well-formed UTF-8 (utf8.h), no control characters (a newline in an id splits log lines and CSV
// rows) and at most `max_bytes` bytes. `quote` false for values that must not reach a log (patient
// names): the message then describes the value without showing it.
Status check_text(std::string_view text, size_t max_bytes, bool quote = true);
// A required identifier: not empty, and check_text within kMaxIdBytes.
Status check_id(std::string_view id);

}  // namespace soiq
