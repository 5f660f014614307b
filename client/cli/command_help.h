#pragma once
// The help texts of `soiq`, printed from the command table (command_table.h): the overview of
// `soiq help` (every command with its summary, the connection options, the exit codes) and one
// command's help for `soiq help CMD`, `soiq CMD --help` and `soiq CMD -h` (synopsis, description,
// options with their defaults, examples, exit codes).
// Errors: help_topic returns INVALID_ARGUMENT "unknown command 'x'; did you mean 'y'?" for a topic
// that is no command. Pure; thread-safe.

#include <string>
#include <string_view>

#include "client/cli/command_table.h"
#include "core/base/status.h"

namespace soiq::cli {

std::string overview_help();

std::string command_help(const CommandSpec& command);

// The help of `topic`: a command ("query", "pacs find"), or "pacs" for all its subcommands.
Result<std::string> help_topic(std::string_view topic);

// The exit codes as one paragraph (client/cli/exit_code.cpp maps them).
std::string_view exit_code_text();

// `text` wrapped at `width` columns, each line after `indent` blanks.
std::string wrap(std::string_view text, size_t indent, size_t width = 100);

}  // namespace soiq::cli
