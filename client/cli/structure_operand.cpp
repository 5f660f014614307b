#include "client/cli/structure_operand.h"

#include <filesystem>
#include <system_error>

#include "client/cli/remote_options.h"

namespace soiq::cli {

Result<OperandKind> structure_operand_kind(const std::string& operand, bool file_exists) {
  if (operand.starts_with(kStructureIdPrefix)) return OperandKind::kStored;
  if (!is_structure_id(operand)) return OperandKind::kFile;
  if (!file_exists) return OperandKind::kStored;
  return invalid_argument("'" + operand + "' is both a structure id and a file here: write " +
                          std::string(kStructureIdPrefix) + operand + " for the stored structure or ./" + operand +
                          " for the file");
}

Result<OperandKind> structure_operand_kind(const std::string& operand) {
  std::error_code ec;
  const bool exists = !operand.empty() && std::filesystem::exists(operand, ec);
  return structure_operand_kind(operand, exists);
}

Status refuse_stored_only_option(const std::string& option, const std::string& command) {
  if (option != "--series" && option != "--series-modality") return ok_status();
  return invalid_argument(option + " applies to a stored structure: soiq " + command + " ID " + option +
                          (option == "--series" ? " UID" : " M") + " (the operand here is a file, or missing)");
}

}  // namespace soiq::cli
