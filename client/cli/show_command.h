#pragma once
// `soiq show patient ID | study UID | structure ID [--format text|json]`: one record from soiqd,
// as "key  value" lines or as the API's JSON object. Exit 3 when it does not exist.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_show_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
