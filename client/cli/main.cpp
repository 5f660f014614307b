// `soiq`: the command-line client. Commands are rows of one table (client/cli/command_table.h);
// this dispatches from it: the global options are taken out, -h/--help prints the row's help,
// options the row does not list are refused with a suggestion, and the row's function runs.
#include <cstdio>
#include <new>
#include <string>

#include "client/cli/check_options.h"
#include "client/cli/command_help.h"
#include "client/cli/command_table.h"
#include "client/cli/exit_code.h"
#include "client/cli/remote_options.h"
#include "core/base/did_you_mean.h"

namespace {

int dispatch(int argc, char** argv);

}  // namespace

// Estimates refuse what cannot fit before it is allocated; this is the last line for what they do
// not cover (a bad_alloc must still end in one readable line and the RESOURCE_EXHAUSTED code).
int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "soiq: out of memory: the input needs more than this machine can give (try a coarser --spacing "
                 "or a smaller --margin)\n");
    return soiq::cli::exit_code(soiq::resource_exhausted(""));
  }
}

namespace {

using namespace soiq::cli;

// One line on stderr, "soiq[ NAME]: message", and the status's exit code.
int fail(const std::string& name, const soiq::Status& s) {
  std::fprintf(stderr, "soiq%s: %s\n", name.empty() ? "" : (" " + name).c_str(), s.message().c_str());
  return exit_code(s);
}

// The row argv names and the index of its first own argument; nullptr (after printing why) when
// it names none. `soiq pacs` without a known subcommand is left to its parser's message.
const CommandSpec* command_of(int argc, char** argv, int& from, int& status) {
  const std::string word = argv[1];
  from = 2;
  if (word == "pacs" && argc > 2 && argv[2][0] != '-') {
    from = 3;
    if (const CommandSpec* c = find_command("pacs " + std::string(argv[2]))) return c;
    std::vector<std::string> verbs;
    for (const CommandSpec& c : command_table())
      if (c.name.starts_with("pacs ")) verbs.emplace_back(c.name.substr(5));
    status = fail("pacs", soiq::invalid_argument("unknown pacs command '" + std::string(argv[2]) + "'" +
                                                 soiq::did_you_mean(argv[2], verbs) + " (echo, find, pull, push)"));
    return nullptr;
  }
  if (word == "pacs") {
    // `soiq pacs`, `soiq pacs --help`: the subcommands' help, or the parser's "missing what to do".
    for (int i = 2; i < argc; ++i) {
      if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
        std::fputs(help_topic("pacs")->c_str(), stdout);
        status = 0;
        return nullptr;
      }
    }
    from = argc;  // nothing to hold to a row: run_pacs_command says what is missing
    return find_command("pacs echo");
  }
  if (const CommandSpec* c = find_command(word)) return c;
  status = fail("", soiq::invalid_argument("unknown command '" + word + "'" +
                                           soiq::did_you_mean(word, command_words()) + " (try 'soiq help')"));
  return nullptr;
}

int dispatch(int argc, char** argv) {
  const soiq::Result<soiq::client::ClientOptions> remote = take_remote_options(argc, argv);
  if (!remote.ok()) {
    std::fprintf(stderr, "soiq: %s (usage: soiq help)\n", remote.status().message().c_str());
    return kExitUsage;
  }
  if (argc < 2) {
    std::fputs(overview_help().c_str(), stderr);
    return kExitUsage;
  }
  if (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(overview_help().c_str(), stdout);
    return 0;
  }
  int from = 2, status = kExitUsage;
  const CommandSpec* command = command_of(argc, argv, from, status);
  if (!command) return status;
  if (asks_for_help(*command, argc, argv, from)) {
    std::fputs(command_help(*command).c_str(), stdout);
    return 0;
  }
  const soiq::Status options = check_options(*command, argc, argv, from);
  if (!options.ok()) {
    const std::string name(command->name);
    return fail(name, soiq::invalid_argument(options.message() + " (soiq " + name + " --help lists them)"));
  }
  return command->run(argc - 1, argv + 1, *remote);
}

}  // namespace
