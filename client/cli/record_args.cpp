#include "client/cli/record_args.h"

namespace soiq::cli {

Result<std::string> option_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) return invalid_argument(std::string(argv[i]) + " needs a value");
  return std::string(argv[++i]);
}

Result<bool> parse_text_or_json(const std::string& text) {
  if (text == "json") return true;
  if (text == "text") return false;
  return invalid_argument("--format must be text or json, got '" + text + "'");
}

Status in_upload_option_words(const Status& status) {
  static const std::pair<const char*, const char*> kOptions[] = {
      {"patient.patient_id", "--patient"},    {"patient.sex", "--sex"},
      {"patient.birth_date", "--birth-date"}, {"study.study_uid", "--study"},
      {"study.study_date", "--study-date"},   {"study.modality", "--modality"},
      {"study.description", "--description"}, {"structure_name", "--name"},
      {"laterality", "--laterality"}};
  for (const auto& [field, option] : kOptions) {
    if (status.field() == field) return Status(status.code(), std::string(option) + ": " + status.reason());
  }
  return status;
}

Status in_option(const Status& status, const std::string& option) {
  return status.ok() ? status : Status(status.code(), option + ": " + status.message());
}

Result<bool> parse_record_option(int argc, char** argv, int& i, soiq::v1::Patient& patient, soiq::v1::Study& study) {
  const std::string arg = argv[i];
  if (arg != "--patient" && arg != "--study" && arg != "--sex" && arg != "--birth-date" && arg != "--study-date" &&
      arg != "--modality" && arg != "--description") {
    return false;
  }
  SOIQ_ASSIGN_OR_RETURN(const std::string value, option_value(argc, argv, i));
  if (arg == "--patient") {
    SOIQ_RETURN_IF_ERROR(in_option(check_id(value), arg));
    patient.set_patient_id(value);
  } else if (arg == "--study") {
    SOIQ_RETURN_IF_ERROR(in_option(check_id(value), arg));
    study.set_study_uid(value);
  } else if (arg == "--sex") {
    SOIQ_RETURN_IF_ERROR(in_option(check_sex(value), arg));
    patient.set_sex(value);
  } else if (arg == "--birth-date") {
    SOIQ_RETURN_IF_ERROR(in_option(check_date(value), arg));
    patient.set_birth_date(value);
  } else if (arg == "--study-date") {
    SOIQ_RETURN_IF_ERROR(in_option(check_date(value), arg));
    study.set_study_date(value);
  } else if (arg == "--modality") {
    SOIQ_RETURN_IF_ERROR(in_option(check_text(value, kMaxIdBytes), arg));
    study.set_modality(value);
  } else {
    SOIQ_RETURN_IF_ERROR(in_option(check_text(value, kMaxNameBytes), arg));
    study.set_description(value);
  }
  return true;
}

Status check_record(const soiq::v1::Patient& patient, const soiq::v1::Study& study) {
  if (patient.patient_id().empty()) return invalid_argument("missing --patient ID");
  if (study.study_uid().empty()) return invalid_argument("missing --study UID");
  return ok_status();
}

}  // namespace soiq::cli
