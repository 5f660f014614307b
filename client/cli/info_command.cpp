#include "client/cli/info_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/feature_list_output.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/show_records.h"

namespace soiq::cli {

namespace {

struct InfoArgs {
  bool json = false;
  bool features = false;  // --features: the server's feature catalogue instead
};

Result<InfoArgs> parse_info_args(int argc, char** argv) {
  InfoArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--features") {
      a.features = true;
      continue;
    }
    if (arg != "--format") return invalid_argument("unexpected argument '" + arg + "'");
    if (i + 1 >= argc) return invalid_argument("--format needs a value");
    SOIQ_ASSIGN_OR_RETURN(a.json, parse_text_or_json(argv[++i]));
  }
  return a;
}

Status info(const InfoArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  SOIQ_ASSIGN_OR_RETURN(const soiq::v1::ServerInfo i, c.server_info());
  if (a.features && !a.json) {
    print_feature_list(server_rows(i), "table");
  } else if (a.json) {
    std::puts(record_json(i).c_str());
  } else {
    std::printf("%-22s %s\n", "server", c.address().c_str());
    print_server_info(i);
  }
  return ok_status();
}

}  // namespace

int run_info_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_command("info", parse_info_args(argc, argv), [&](const InfoArgs& a) { return info(a, remote); });
}

}  // namespace soiq::cli
