#pragma once
// The one table of `soiq`'s commands: for each command and `pacs` subcommand its name, synopsis,
// summary, description, options, examples and the function that runs it. main.cpp dispatches from
// it, check_options.h refuses any option it does not list (so a parser never sees an option the
// help does not show), and help, bash completion and the man page are printed from it.
// The rows live by command group in command_table_*.cpp; tests/client/command_table_test.cpp holds
// each parser's source to its row.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "client/soiq_client.h"

namespace soiq::cli {

struct OptionSpec {
  std::string_view name;           // "--select", "-o"
  std::string_view value;          // placeholder of its value ("FEATURE"); "" for a flag
  std::string_view default_value;  // "" when it has none (or is off)
  std::string_view meaning;
  std::string_view alias = "";  // another spelling ("--output" for "-o")
};

// Runs a command: argv[0] is the command's name ("pacs" for its subcommands); the exit status.
using CommandRunner = int (*)(int argc, char** argv, const client::ClientOptions& remote);

enum class CommandGroup { kOffline, kRemote, kOther };

struct CommandSpec {
  std::string_view name;  // "query", "pacs find"
  CommandGroup group;
  std::vector<std::string_view> synopsis;  // lines after "soiq "
  std::string_view summary;                // one line, for the overview
  std::string_view description;            // one paragraph
  std::vector<OptionSpec> options;         // besides -h/--help and the connection options
  std::vector<std::string_view> examples;  // whole command lines
  CommandRunner run = nullptr;
  bool hidden = false;                  // not in the overview (man)
  std::string_view overview_note = "";  // what the overview says beyond the summary
};

// Every command, in help order.
std::span<const CommandSpec> command_table();

// The row named `name` ("query", "pacs find"), or nullptr.
const CommandSpec* find_command(std::string_view name);

// The option of `command` spelled `name` (or its alias), or nullptr.
const OptionSpec* find_option(const CommandSpec& command, std::string_view name);

// The names to suggest from: the top-level command words ("pacs" once), and a command's option
// spellings.
std::vector<std::string> command_words();
std::vector<std::string> option_words(const CommandSpec& command);

// The options every command takes, before or after its name (client/cli/remote_options.h): the
// connection's and --quiet.
std::span<const OptionSpec> global_options();

// The rows of the groups, defined in command_table_<group>.cpp.
std::vector<CommandSpec> offline_commands();
std::vector<CommandSpec> record_commands();
std::vector<CommandSpec> pacs_commands();
std::vector<CommandSpec> query_commands();
std::vector<CommandSpec> other_commands();

}  // namespace soiq::cli
