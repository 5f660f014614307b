#pragma once
// `soiq completion bash`: a bash completion script made from the command table (command_table.h):
// command words, each command's options, the values of options with a closed set of them
// (--format table|json|csv), region words, and feature names (core/features/feature_catalogue.h)
// after --features, --select, --order-by and --where. The build writes it to completion/soiq and
// `cmake --install` puts it in share/bash-completion/completions.

#include <string>

#include "client/soiq_client.h"

namespace soiq::cli {

std::string bash_completion_script();

// Prints the script for `completion bash`; exit 2 for any other shell.
int run_completion_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
