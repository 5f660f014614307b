#include "client/cli/health_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/remote_options.h"

namespace soiq::cli {
namespace {

struct HealthArgs {};

Result<HealthArgs> parse_health_args(int argc, char** argv) {
  if (argc > 1) return invalid_argument(std::string("unexpected argument '") + argv[1] + "'");
  return HealthArgs{};
}

Status health(const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  SOIQ_ASSIGN_OR_RETURN(const bool serving, c.serving());
  if (!serving) return Status(StatusCode::kUnavailable, "soiqd at " + c.address() + " is NOT_SERVING");
  std::puts("SERVING");
  return ok_status();
}

}  // namespace

int run_health_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_command("health", parse_health_args(argc, argv), [&](const HealthArgs&) { return health(remote); });
}

}  // namespace soiq::cli
