#include "client/cli/help_command.h"

#include <cstdio>
#include <string>

#include "client/cli/command_help.h"
#include "client/cli/exit_code.h"

namespace soiq::cli {

int run_help_command(int argc, char** argv, const client::ClientOptions&) {
  if (argc < 2) {
    std::fputs(overview_help().c_str(), stdout);
    return 0;
  }
  std::string topic = argv[1];  // "help pacs find" names a subcommand
  for (int i = 2; i < argc; ++i) topic += std::string(" ") + argv[i];
  const Result<std::string> help = help_topic(topic);
  if (!help.ok()) {
    std::fprintf(stderr, "soiq help: %s\n", help.status().message().c_str());
    return exit_code(help.status());
  }
  std::fputs(help->c_str(), stdout);
  return 0;
}

}  // namespace soiq::cli
