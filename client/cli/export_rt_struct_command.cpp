#include "client/cli/export_rt_struct_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"

namespace soiq::cli {
namespace export_rt_struct_args {

namespace v1 = soiq::v1;

struct ExportRtStructArgs {
  v1::ExportRtStructRequest request;
  std::string out;
};

Result<ExportRtStructArgs> parse(int argc, char** argv) {
  ExportRtStructArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(a.out, option_value(argc, argv, i));
    } else if (arg == "--description") {
      SOIQ_ASSIGN_OR_RETURN(*a.request.mutable_series_description(), option_value(argc, argv, i));
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else {
      SOIQ_ASSIGN_OR_RETURN(const int64_t id, parse_structure_id(arg));
      a.request.add_structure_ids(id);
    }
  }
  if (a.request.structure_ids().empty()) return invalid_argument("missing structure ID");
  if (a.out.empty()) return invalid_argument("missing -o OUT.dcm");
  return a;
}

Status export_rt_struct(const ExportRtStructArgs& a, const client::ClientOptions& remote) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  const Result<v1::RtStructInfo> written = c.export_rt_struct(a.request, a.out);
  if (!written.ok() && interrupted()) return interrupted_by_user("no file was written");
  SOIQ_ASSIGN_OR_RETURN(const v1::RtStructInfo info, written);
  std::printf("DICOM RT Structure Set %s: %d ROI%s, %lld contours, %lld points, %lld bytes, on series %s -> %s\n",
              info.sop_instance_uid().c_str(), info.rois(), info.rois() == 1 ? "" : "s", (long long)info.contours(),
              (long long)info.points(), (long long)info.size_bytes(), info.referenced_series_uid().c_str(),
              a.out.c_str());
  return ok_status();
}

}  // namespace export_rt_struct_args

int run_export_rt_struct_command(int argc, char** argv, const client::ClientOptions& remote) {
  namespace e = export_rt_struct_args;
  return run_long_command("export-rtstruct", e::parse(argc, argv), remote,
                          [](const e::ExportRtStructArgs& a, const client::ClientOptions& options) {
                            return e::export_rt_struct(a, options);
                          });
}

}  // namespace soiq::cli
