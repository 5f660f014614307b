#pragma once
// `soiq health`: asks soiqd's standard health service (grpc.health.v1) whether it is serving; the
// container's HEALTHCHECK. Prints SERVING and exits 0, or NOT_SERVING and exits 6 (unavailable).

#include "client/soiq_client.h"

namespace soiq::cli {

int run_health_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
