#pragma once
// `soiq rm structure ID | patient ID`: deletes a structure, or a patient with all its studies,
// series and structures, on soiqd. Prints "deleted N structure(s)". Exit 3 when it does not exist.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_rm_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
