#include "client/cli/upload_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/precompute_wait.h"
#include "client/cli/progress_bar.h"
#include "client/cli/quiet.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"

namespace soiq::cli {

namespace {

struct UploadArgs {
  std::string mesh;
  soiq::v1::UploadSurfaceHeader header;
  bool wait = false;
};

Result<UploadArgs> parse_upload_args(int argc, char** argv) {
  UploadArgs a;
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool record,
                          parse_record_option(argc, argv, i, *a.header.mutable_patient(), *a.header.mutable_study()));
    if (record) continue;
    const std::string arg = argv[i];
    if (arg == "--name") {
      SOIQ_ASSIGN_OR_RETURN(*a.header.mutable_structure_name(), option_value(argc, argv, i));
    } else if (arg == "--laterality") {
      SOIQ_ASSIGN_OR_RETURN(const std::string l, option_value(argc, argv, i));
      SOIQ_RETURN_IF_ERROR(in_option(check_laterality(l), arg));
      a.header.set_laterality(l);
    } else if (arg == "--ras") {
      a.header.set_coordinates(soiq::v1::RAS);
    } else if (arg == "--robust") {
      a.header.set_robust(true);
    } else if (arg == "--wait") {
      a.wait = true;
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (a.mesh.empty()) {
      a.mesh = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "' (one MESH per upload)");
    }
  }
  if (a.mesh.empty()) return invalid_argument("missing MESH");
  if (!is_mesh_path(a.mesh)) {
    return invalid_argument("'" + a.mesh + "' is not a surface model; use .stl, .obj, .ply, .vtk or .vtp");
  }
  SOIQ_RETURN_IF_ERROR(check_record(a.header.patient(), a.header.study()));
  if (a.header.structure_name().empty()) return invalid_argument("missing --name NAME (e.g. hippocampus)");
  return a;
}

Status upload(const UploadArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  ProgressBar bar;
  const Result<soiq::v1::UploadSurfaceResponse> uploaded =
      c.upload_surface(a.header, a.mesh, [&](int64_t done, int64_t total) { bar.update("sending", done, total); });
  bar.clear();
  if (!uploaded.ok() && interrupted()) return interrupted_by_user("nothing was stored");
  if (!uploaded.ok()) return in_upload_option_words(uploaded.status());
  const soiq::v1::UploadSurfaceResponse& r = *uploaded;
  const soiq::v1::Structure& s = r.structure();
  if (a.wait) SOIQ_RETURN_IF_ERROR(wait_option(c));
  if (quiet()) {
    std::printf("%lld\n", (long long)s.id());
    return ok_status();
  }
  std::printf("structure %lld: %s%s%s of patient %s, study %s; %lld triangles; %s%s%s\n", (long long)s.id(),
              s.name().c_str(), s.laterality().empty() ? "" : " ", s.laterality().c_str(), s.patient_id().c_str(),
              s.study_uid().c_str(), (long long)s.triangle_count(),
              r.surface_already_stored() ? "surface already stored (deduplicated)" : "new surface",
              r.defects().empty() ? "" : "; ", r.defects().c_str());
  return ok_status();
}

}  // namespace

int run_upload_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command("upload", parse_upload_args(argc, argv), remote,
                          [](const UploadArgs& a, const client::ClientOptions& options) { return upload(a, options); });
}

}  // namespace soiq::cli
