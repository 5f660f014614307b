#pragma once
// The options that describe a patient and a study on the command line, shared by `soiq upload`
// and `soiq upload-image`: --patient ID --study UID [--sex M|F|O] [--birth-date YYYYMMDD]
// [--study-date YYYYMMDD] [--modality MR] [--description TEXT], each checked by its field's one
// rule (core/base/field_rules.h), as soiqd checks it again.

#include <string>

#include "core/base/field_rules.h"
#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

// When argv[i] is one of the options above, stores its value (advancing i) and returns true.
Result<bool> parse_record_option(int argc, char** argv, int& i, soiq::v1::Patient& patient, soiq::v1::Study& study);

// INVALID_ARGUMENT unless --patient and --study were given.
Status check_record(const soiq::v1::Patient& patient, const soiq::v1::Study& study);

// soiqd's error about a field of an upload's header ("patient.birth_date") as the option that set
// it ("--birth-date: ..."), from Status::field(); other errors unchanged.
Status in_upload_option_words(const Status& status);

// A field rule's error (core/base/field_rules.h) as the option's: "--birth-date: '20230231' is not
// a calendar date YYYYMMDD". OK stays OK.
Status in_option(const Status& status, const std::string& option);

// --format text|json of show and info: true for json. INVALID_ARGUMENT otherwise.
Result<bool> parse_text_or_json(const std::string& text);

// The value after argv[i] (advancing i), or INVALID_ARGUMENT "<flag> needs a value".
Result<std::string> option_value(int argc, char** argv, int& i);

}  // namespace soiq::cli
