#include "client/cli/download_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"

namespace soiq::cli {

namespace {

struct DownloadArgs {
  soiq::v1::DownloadSurfaceRequest request;
  std::string out;
};

Result<DownloadArgs> parse_download_args(int argc, char** argv) {
  DownloadArgs a;
  std::string id;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(a.out, option_value(argc, argv, i));
    } else if (arg == "--ras") {
      a.request.set_coordinates(soiq::v1::RAS);
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (id.empty()) {
      id = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (id.empty()) return invalid_argument("missing structure ID");
  SOIQ_ASSIGN_OR_RETURN(const int64_t structure_id, parse_structure_id(id));
  a.request.set_id(structure_id);
  if (a.out.empty()) return invalid_argument("missing -o OUT.{stl,obj,ply,vtk,vtp}");
  if (!is_mesh_path(a.out)) {
    return invalid_argument("output '" + a.out + "' has an unknown extension; use .stl, .obj, .ply, .vtk or .vtp");
  }
  return a;
}

Status download(const DownloadArgs& a, const client::ClientOptions& remote) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  const Result<int64_t> written = c.download_surface(a.request, a.out);
  if (!written.ok() && interrupted()) return interrupted_by_user("no file was written");
  SOIQ_ASSIGN_OR_RETURN(const int64_t bytes, written);
  std::printf("%lld bytes -> %s\n", (long long)bytes, a.out.c_str());
  return ok_status();
}

}  // namespace

int run_download_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command(
      "download", parse_download_args(argc, argv), remote,
      [](const DownloadArgs& a, const client::ClientOptions& options) { return download(a, options); });
}

}  // namespace soiq::cli
