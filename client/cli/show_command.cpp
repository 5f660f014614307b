#include "client/cli/show_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/show_records.h"

namespace soiq::cli {

namespace {

struct ShowArgs {
  std::string kind, key;
  bool json = false;
};

Result<ShowArgs> parse_show_args(int argc, char** argv) {
  ShowArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--format") {
      if (i + 1 >= argc) return invalid_argument("--format needs a value");
      SOIQ_ASSIGN_OR_RETURN(a.json, parse_text_or_json(argv[++i]));
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (a.kind.empty() && (is_structure_id(arg) || arg.starts_with(kStructureIdPrefix))) {
      a.kind = "structure";  // `soiq show 121`: a bare id is a structure, as in the rest of the CLI
      a.key = arg;
    } else if (a.kind.empty()) {
      if (arg != "patient" && arg != "study" && arg != "structure") {
        return invalid_argument("show what? patient ID, study UID or structure ID, got '" + arg + "'");
      }
      a.kind = arg;
    } else if (a.key.empty()) {
      a.key = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (a.kind.empty() || a.key.empty()) return invalid_argument("needs patient ID, study UID or structure ID");
  if (a.kind == "structure") SOIQ_RETURN_IF_ERROR(parse_structure_id(a.key).status());
  return a;
}

Status show(const ShowArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  if (a.kind == "patient") {
    SOIQ_ASSIGN_OR_RETURN(const soiq::v1::Patient p, c.get_patient(a.key));
    a.json ? (void)std::puts(record_json(p).c_str()) : print_patient(p);
  } else if (a.kind == "study") {
    SOIQ_ASSIGN_OR_RETURN(const soiq::v1::Study s, c.get_study(a.key));
    a.json ? (void)std::puts(record_json(s).c_str()) : print_study(s);
  } else {
    SOIQ_ASSIGN_OR_RETURN(const int64_t id, parse_structure_id(a.key));
    SOIQ_ASSIGN_OR_RETURN(const soiq::v1::Structure s, c.get_structure(id));
    a.json ? (void)std::puts(record_json(s).c_str()) : print_structure(s);
  }
  return ok_status();
}

}  // namespace

int run_show_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_command("show", parse_show_args(argc, argv), [&](const ShowArgs& a) { return show(a, remote); });
}

}  // namespace soiq::cli
