#pragma once
// `soiq info [--format text|json] [--features]`: soiqd's version, limits and record counts
// (GetServerInfo); --features: the features it computes, as `soiq features --list` prints them.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_info_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
