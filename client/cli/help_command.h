#pragma once
// `soiq help [COMMAND]`: the overview, or one command's help (command_help.h), on stdout, exit 0;
// an unknown COMMAND is one line on stderr with the closest command, exit 2.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_help_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
