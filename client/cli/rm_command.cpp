#include "client/cli/rm_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/remote_options.h"

namespace soiq::cli {

namespace {

struct RmArgs {
  std::string kind, key;
};

Result<RmArgs> parse_rm_args(int argc, char** argv) {
  RmArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 1 && arg[0] == '-') return invalid_argument("unknown option '" + arg + "'");
    if (a.kind.empty()) {
      // A bare id is not taken for a structure here as `soiq show` takes it: a delete says what it deletes.
      if (is_structure_id(arg)) return invalid_argument("rm what? write 'soiq rm structure " + arg + "' (or patient)");
      if (arg != "structure" && arg != "patient") {
        return invalid_argument("rm what? structure ID or patient ID, got '" + arg + "'");
      }
      a.kind = arg;
    } else if (a.key.empty()) {
      a.key = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "' (one record at a time)");
    }
  }
  if (a.key.empty()) return invalid_argument("needs structure ID or patient ID");
  if (a.kind == "structure") SOIQ_RETURN_IF_ERROR(parse_structure_id(a.key).status());
  return a;
}

Status rm(const RmArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  soiq::v1::DeleteResponse r;
  if (a.kind == "structure") {
    SOIQ_ASSIGN_OR_RETURN(const int64_t id, parse_structure_id(a.key));
    SOIQ_ASSIGN_OR_RETURN(r, c.delete_structure(id));
  } else {
    SOIQ_ASSIGN_OR_RETURN(r, c.delete_patient(a.key));
  }
  std::printf("deleted %lld structure%s\n", (long long)r.structures_deleted(), r.structures_deleted() == 1 ? "" : "s");
  return ok_status();
}

}  // namespace

int run_rm_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_command("rm", parse_rm_args(argc, argv), [&](const RmArgs& a) { return rm(a, remote); });
}

}  // namespace soiq::cli
