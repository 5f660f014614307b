#include "client/cli/convert_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/exit_code.h"
#include "client/cli/mesh_on_grid.h"
#include "client/cli/structure_operand.h"
#include "core/io/write_image.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::cli {

namespace {

struct ConvertArgs {
  std::string mesh, out;
  MeshGridOptions grid;
};

Result<ConvertArgs> parse_convert_args(int argc, char** argv) {
  ConvertArgs a;
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool shared, parse_mesh_grid_option(argc, argv, i, a.grid));
    if (shared) continue;
    const std::string arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      if (i + 1 >= argc) return invalid_argument("-o needs a value");
      a.out = argv[++i];
    } else if (!arg.empty() && arg[0] == '-') {
      SOIQ_RETURN_IF_ERROR(refuse_stored_only_option(arg, "convert"));
      return invalid_argument("unknown option '" + arg + "'");
    } else if (a.mesh.empty()) {
      a.mesh = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (a.mesh.empty()) return invalid_argument("missing MESH");
  if (a.out.empty()) return invalid_argument("missing -o OUT");
  // Refuse an unwritable format before any work is done, not after.
  const bool known_format =
      ends_with(a.out, ".nii.gz") || ends_with(a.out, ".nii") || ends_with(a.out, ".nrrd") || ends_with(a.out, ".mha");
  if (!known_format) {
    return invalid_argument("output '" + a.out + "' has an unknown extension; use .nii.gz, .nii, .nrrd or .mha");
  }
  SOIQ_RETURN_IF_ERROR(check_mesh_grid_options(a.grid));
  return a;
}

Status convert(const ConvertArgs& a) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  SOIQ_ASSIGN_OR_RETURN(const MeshOnGrid m, convert_mesh_file(a.mesh, a.grid));
  SOIQ_ASSIGN_OR_RETURN(const Mask mask, to_mask(m.voxels.volume));
  SOIQ_RETURN_IF_ERROR(write_mask(mask, a.out));
  const int64_t n = voxel_count(m.voxels.volume);
  std::printf("%lld voxels inside, %.3f mm3 on %s; %s%s; %.2f ms%s -> %s\n", (long long)n,
              double(n) * m.grid.voxel_volume_mm3(), describe(m.grid).c_str(), describe(m.voxels.defects).c_str(),
              m.flipped ? ", orientation flipped to outward" : "", m.milliseconds, a.grid.robust ? " (robust)" : "",
              a.out.c_str());
  return ok_status();
}

}  // namespace

int run_convert_command(int argc, char** argv) {
  return run_command("convert", parse_convert_args(argc, argv), convert);
}

}  // namespace soiq::cli
