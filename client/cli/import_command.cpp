#include "client/cli/import_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "client/cli/cli_args.h"
#include "client/cli/import_report.h"
#include "client/cli/precompute_wait.h"
#include "client/cli/progress_bar.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/row_printer.h"

namespace soiq::cli {

namespace {

namespace v1 = soiq::v1;

struct ImportArgs {
  std::vector<std::string> paths;
  std::string format = "table";
  bool wait = false;
  bool replace = false;
};

Result<ImportArgs> parse_import_args(int argc, char** argv) {
  ImportArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--format") {
      SOIQ_ASSIGN_OR_RETURN(a.format, option_value(argc, argv, i));
      SOIQ_RETURN_IF_ERROR(check_row_format(a.format));
    } else if (arg == "--wait") {
      a.wait = true;
    } else if (arg == "--replace") {
      a.replace = true;
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else {
      a.paths.push_back(arg);
    }
  }
  if (a.paths.empty()) return invalid_argument("missing PATH (DICOM files or folders)");
  return a;
}

Status import(const ImportArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  ProgressBar bar;
  bool sent_all = false;
  auto r = c.import_dicom(
      a.paths,
      [&](int64_t done, int64_t total) {
        bar.update("sending", done, total);
        sent_all = done == total;
      },
      a.replace);
  bar.clear();
  if (!r.ok() && interrupted()) {
    // soiqd stores an import only once it has every file, and asks once more just before writing.
    return interrupted_by_user(sent_all ? "soiqd was told to drop the import ('soiq ls studies' shows whether it "
                                          "had stored it already)"
                                        : "nothing was imported");
  }
  if (!r.ok()) return r.status();
  print_import_report(*r, a.format);
  // The series and the other structures are stored; but a structure set given to be imported that
  // gave nothing is a failure a script must see.
  if (r->structure_sets_without_structures_size() > 0) {
    const int n = r->structure_sets_without_structures_size();
    return failed_precondition(std::to_string(n) + (n == 1 ? " structure set" : " structure sets") +
                               " stored no structure (" + r->structure_sets_without_structures(0) +
                               (n > 1 ? ", ..." : "") + "): see the problems above");
  }
  if (a.wait) return wait_option(c);
  return ok_status();
}

}  // namespace

int run_import_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command("import", parse_import_args(argc, argv), remote,
                          [](const ImportArgs& a, const client::ClientOptions& options) { return import(a, options); });
}

}  // namespace soiq::cli
