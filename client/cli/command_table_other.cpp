// The rows of the commands about soiq itself in the command table: help, completion, man.
#include "client/cli/bash_completion.h"
#include "client/cli/command_table.h"
#include "client/cli/help_command.h"
#include "client/cli/man_page.h"

namespace soiq::cli {

std::vector<CommandSpec> other_commands() {
  return {
      {"help",
       CommandGroup::kOther,
       {"help [COMMAND]"},
       "this overview, or one command's help (as 'soiq COMMAND --help')",
       "Prints the overview of every command, or the help of one: synopsis, options with their defaults, "
       "examples and exit codes. 'soiq COMMAND --help' and 'soiq COMMAND -h' print the same.",
       {},
       {"soiq help query", "soiq pacs find --help"},
       run_help_command},
      {"completion",
       CommandGroup::kOther,
       {"completion bash"},
       "a bash completion script for soiq (commands, options, feature names)",
       "Prints a bash completion script made from this command table. Installed as "
       "share/bash-completion/completions/soiq; or load it by hand with: source <(soiq completion bash).",
       {},
       {"source <(soiq completion bash)"},
       run_completion_command},
      {"man",
       CommandGroup::kOther,
       {"man"},
       "the soiq(1) manual page, in roff",
       "Prints the soiq(1) manual page made from this command table, in roff (man -l - reads it).",
       {},
       {"soiq man | man -l -"},
       run_man_command,
       true},
  };
}

}  // namespace soiq::cli
