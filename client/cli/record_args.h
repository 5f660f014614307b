#pragma once
// The options that describe a patient and a study on the command line, shared by `soiq upload`
// and `soiq upload-image`: --patient ID --study UID [--sex M|F|O] [--birth-date YYYYMMDD]
// [--study-date YYYYMMDD] [--modality MR] [--description TEXT]; and the checks of DICOM-style
// values the listing and query commands share.

#include <string>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

// When argv[i] is one of the options above, stores its value (advancing i) and returns true.
Result<bool> parse_record_option(int argc, char** argv, int& i, soiq::v1::Patient& patient, soiq::v1::Study& study);

// INVALID_ARGUMENT unless --patient and --study were given.
Status check_record(const soiq::v1::Patient& patient, const soiq::v1::Study& study);

// INVALID_ARGUMENT "<flag> must be a date YYYYMMDD, got '...'" unless 8 digits of a plausible date.
Status check_date(const std::string& text, const std::string& flag);
// M, F or O.
Status check_sex(const std::string& text);
// L or R.
Status check_laterality(const std::string& text);

// --format text|json of show and info: true for json. INVALID_ARGUMENT otherwise.
Result<bool> parse_text_or_json(const std::string& text);

// The value after argv[i] (advancing i), or INVALID_ARGUMENT "<flag> needs a value".
Result<std::string> option_value(int argc, char** argv, int& i);

}  // namespace soiq::cli
