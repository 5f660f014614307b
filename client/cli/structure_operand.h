#pragma once
// What the operand of `soiq convert` and `soiq features` names: a structure stored in soiqd (the
// command runs there) or a mesh file on this machine (the command runs offline).
//
// Inputs   the operand as typed, and whether a file of that name exists here (the caller asks the
//          file system, so the rule itself is testable without one).
// Output   kStored for `id:N`, or for N (all digits) when no file N exists; kFile for anything
//          else: a path, a name with an extension, `./123`.
// Errors   INVALID_ARGUMENT when N is all digits and a file N exists too, naming both ways to say
//          which is meant (`id:N` or `./N`): guessing would convert the wrong thing without a word.
// Caveats  `id:N` with N not a whole number > 0 is kStored here and refused by parse_structure_id.

#include <string>

#include "core/base/status.h"

namespace soiq::cli {

enum class OperandKind { kStored, kFile };

Result<OperandKind> structure_operand_kind(const std::string& operand, bool file_exists);

// The same, asking the file system whether `operand` exists as a file.
Result<OperandKind> structure_operand_kind(const std::string& operand);

// The offline parsers' word for an option only the stored form takes (--series, --series-modality):
// INVALID_ARGUMENT saying so ("--series applies to a stored structure: soiq convert ID --series UID"),
// rather than calling a documented option unknown. OK for any other option.
Status refuse_stored_only_option(const std::string& option, const std::string& command);

}  // namespace soiq::cli
