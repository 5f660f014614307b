#pragma once
// `soiq info [--format text|json]`: soiqd's version, limits and record counts (GetServerInfo).

#include "client/soiq_client.h"

namespace soiq::cli {

int run_info_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
