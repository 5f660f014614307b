#pragma once
// A patient's age at a study, in years, from what the DICOM files carry (docs/DESIGN.md "DICOM and
// PACS": stage 1 filters on age at study, which files give as Patient's Age or through dates).
//
// Inputs   patient_age: Patient's Age (0010,1010), VR AS "nnnD", "nnnW", "nnnM" or "nnnY";
//          birth_date, study_date: DA "YYYYMMDD"; any may be "".
// Output   From Patient's Age when it is well formed: nnnY -> nnn, nnnM -> nnn/12,
//          nnnW -> nnn*7/365.25, nnnD -> nnn/365.25. Otherwise from the dates: completed years
//          plus the fraction of the year since the last birthday (days since it / days from it to
//          the next one), so the age is an integer on each birthday; a 29 February birthday falls
//          on 28 February in common years. nullopt when neither source gives an age (missing or
//          malformed values, or a study before the birth).
// Cost     O(1); thread-safe.

#include <optional>
#include <string>

namespace soiq::dicom {

std::optional<double> age_at_study(const std::string& patient_age, const std::string& birth_date,
                                   const std::string& study_date);

// Patient's Age alone (nullopt when not nnn[DWMY]).
std::optional<double> parse_patient_age(const std::string& patient_age);

}  // namespace soiq::dicom
