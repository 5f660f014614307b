#include "client/cli/export_seg_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/fraction_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"

namespace soiq::cli {
namespace {

namespace v1 = soiq::v1;

struct ExportSegArgs {
  v1::ExportSegRequest request;
  std::string out;
  FractionArgs fractions;  // --fractional, --oversample (a SEG's fractions are always bytes)
};

Result<ExportSegArgs> parse_export_seg_args(int argc, char** argv) {
  ExportSegArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(a.out, option_value(argc, argv, i));
    } else if (arg == "--description") {
      SOIQ_ASSIGN_OR_RETURN(*a.request.mutable_series_description(), option_value(argc, argv, i));
    } else if (arg.size() > 1 && arg[0] == '-') {
      SOIQ_ASSIGN_OR_RETURN(const bool fraction_option, parse_fraction_option(argc, argv, i, a.fractions));
      if (fraction_option) continue;
      return invalid_argument("unknown option '" + arg + "'");
    } else {
      SOIQ_ASSIGN_OR_RETURN(const int64_t id, parse_structure_id(arg));
      a.request.add_structure_ids(id);
    }
  }
  if (a.request.structure_ids().empty()) return invalid_argument("missing structure ID");
  if (a.out.empty()) return invalid_argument("missing -o OUT.dcm");
  SOIQ_RETURN_IF_ERROR(check_fraction_args(a.fractions));
  if (a.fractions.fractional) a.request.set_oversample(a.fractions.lines_per_voxel());
  return a;
}

Status export_seg(const ExportSegArgs& a, const client::ClientOptions& remote) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  const Result<v1::SegInfo> written = c.export_seg(a.request, a.out);
  if (!written.ok() && interrupted()) return interrupted_by_user("no file was written");
  SOIQ_ASSIGN_OR_RETURN(const v1::SegInfo info, written);
  const std::string kind = a.request.oversample() > 0
                               ? " (FRACTIONAL, " + std::to_string(a.request.oversample()) + "x" +
                                     std::to_string(a.request.oversample()) + " lines per voxel)"
                               : "";
  std::printf("DICOM SEG %s%s: %d segment%s, %lld frames, %lld bytes, on series %s -> %s\n",
              info.sop_instance_uid().c_str(), kind.c_str(), info.segments(), info.segments() == 1 ? "" : "s",
              (long long)info.frames(), (long long)info.size_bytes(), info.referenced_series_uid().c_str(),
              a.out.c_str());
  return ok_status();
}

}  // namespace

int run_export_seg_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command(
      "export-seg", parse_export_seg_args(argc, argv), remote,
      [](const ExportSegArgs& a, const client::ClientOptions& options) { return export_seg(a, options); });
}

}  // namespace soiq::cli
