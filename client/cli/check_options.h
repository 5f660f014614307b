#pragma once
// The options on a command line held to the command's row in the command table (command_table.h)
// before its parser runs, so that help and parser cannot disagree: an option the row does not list
// is refused here, with the closest listed one as a suggestion.
//
// Inputs: the row, and argv with the command's own arguments from index `from` (the connection
// options already taken out). The value after an option that takes one (its row has a value
// placeholder) is skipped, whatever it looks like ("--where 'x>-1'"); "--label=3" is "--label".
// Errors: INVALID_ARGUMENT "unknown option '--slect'; did you mean '--select'?".
// Pure; O(argc x options).

#include "client/cli/command_table.h"
#include "core/base/status.h"

namespace soiq::cli {

Status check_options(const CommandSpec& command, int argc, char** argv, int from);

// True when -h or --help stands where an option may (not as another option's value).
bool asks_for_help(const CommandSpec& command, int argc, char** argv, int from);

}  // namespace soiq::cli
