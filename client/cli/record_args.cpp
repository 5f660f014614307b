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

Status check_date(const std::string& text, const std::string& flag) {
  bool digits = text.size() == 8;
  for (const char c : text) digits = digits && c >= '0' && c <= '9';
  if (digits) {
    const int month = std::stoi(text.substr(4, 2)), day = std::stoi(text.substr(6, 2));
    if (month >= 1 && month <= 12 && day >= 1 && day <= 31) return ok_status();
  }
  return invalid_argument(flag + " must be a date YYYYMMDD, got '" + text + "'");
}

Status check_sex(const std::string& text) {
  if (text == "M" || text == "F" || text == "O") return ok_status();
  return invalid_argument("--sex must be M, F or O, got '" + text + "'");
}

Status check_laterality(const std::string& text) {
  if (text == "L" || text == "R") return ok_status();
  return invalid_argument("--laterality must be L or R, got '" + text + "'");
}

Result<bool> parse_record_option(int argc, char** argv, int& i, soiq::v1::Patient& patient, soiq::v1::Study& study) {
  const std::string arg = argv[i];
  if (arg != "--patient" && arg != "--study" && arg != "--sex" && arg != "--birth-date" && arg != "--study-date" &&
      arg != "--modality" && arg != "--description") {
    return false;
  }
  SOIQ_ASSIGN_OR_RETURN(const std::string value, option_value(argc, argv, i));
  if (arg == "--patient") {
    patient.set_patient_id(value);
  } else if (arg == "--study") {
    study.set_study_uid(value);
  } else if (arg == "--sex") {
    SOIQ_RETURN_IF_ERROR(check_sex(value));
    patient.set_sex(value);
  } else if (arg == "--birth-date") {
    SOIQ_RETURN_IF_ERROR(check_date(value, arg));
    patient.set_birth_date(value);
  } else if (arg == "--study-date") {
    SOIQ_RETURN_IF_ERROR(check_date(value, arg));
    study.set_study_date(value);
  } else if (arg == "--modality") {
    study.set_modality(value);
  } else {
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
