#pragma once
// Input checks of the store's records and filters, before any SQL runs: every failure is
// INVALID_ARGUMENT naming the field and the value (identifiers, never patient names).

#include <string>

#include "core/status.h"
#include "db/store.h"

namespace soiq::db {

Status validate_sex(const std::string& sex);                                 // "", "M", "F", "O"
Status validate_laterality(const std::string& laterality);                   // "", "L", "R"
Status validate_sha256(const std::string& sha256, const std::string& what);  // 64 lower-case hex
// "" or a DICOM UID: at most 64 characters, digits and '.' only.
Status validate_uid(const std::string& uid, const std::string& what);
// patient_id non-empty; sex; birth date.
Status validate_patient(const PatientRecord& p);
// study_uid non-empty; study date; age finite and >= 0 when given; patient_id "" or `patient_id`.
Status validate_study(const StudyRecord& s, const std::string& patient_id);
// Sex, laterality, dates; ages finite and min <= max.
Status validate_stage1_filter(const Stage1Filter& f);

}  // namespace soiq::db
