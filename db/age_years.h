#pragma once
// Dates as the store keeps them (DICOM DA: YYYYMMDD) and the age at a study computed from them.

#include <optional>
#include <string>

#include "core/base/status.h"

namespace soiq::db {

// Age in years at `study_date` of a patient born on `birth_date`, both YYYYMMDD:
//   completed years Y (anniversaries of the birth on or before the study date)
//   + (days since the last anniversary) / (days from the last to the next anniversary).
// So the age is exactly an integer on each birthday and grows linearly in between; a patient
// born on 29 February has the anniversary on 28 February in common years.
// nullopt when either date is "" or the study is before the birth (the age is then unknown, not
// negative). INVALID_ARGUMENT for a malformed date.
Result<std::optional<double>> age_years(const std::string& birth_date, const std::string& study_date);

}  // namespace soiq::db
