#include "client/cli/convert_command.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "client/cli/cli_args.h"
#include "client/cli/exit_code.h"
#include "core/grid_around.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/io/write_image.h"
#include "core/voxelize_1d.h"

namespace soiq::cli {

namespace {

struct ConvertArgs {
  std::string mesh, out, reference;
  Vec3 spacing_mm{1, 1, 1};
  bool spacing_given = false;
  int margin = 2;
  bool robust = false, even_odd = false, ras = false;
  int threads = 1;
};

Result<ConvertArgs> parse(int argc, char** argv) {
  ConvertArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) -> Result<std::string> {
      if (i + 1 >= argc) return invalid_argument(std::string(flag) + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(a.out, value("-o"));
    } else if (arg == "--reference") {
      SOIQ_ASSIGN_OR_RETURN(a.reference, value("--reference"));
    } else if (arg == "--spacing") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--spacing"));
      SOIQ_ASSIGN_OR_RETURN(a.spacing_mm, parse_spacing(text));
      a.spacing_given = true;
    } else if (arg == "--margin") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--margin"));
      SOIQ_ASSIGN_OR_RETURN(a.margin, parse_int(text, "--margin", 0, 1000000));
    } else if (arg == "--threads") {
      SOIQ_ASSIGN_OR_RETURN(std::string text, value("--threads"));
      SOIQ_ASSIGN_OR_RETURN(a.threads, parse_int(text, "--threads", 1, 1024));
    } else if (arg == "--robust") {
      a.robust = true;
    } else if (arg == "--even-odd") {
      a.even_odd = true;
    } else if (arg == "--ras") {
      a.ras = true;
    } else if (!arg.empty() && arg[0] == '-') {
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
  if (!known_format)
    return invalid_argument("output '" + a.out + "' has an unknown extension; use .nii.gz, .nii, .nrrd or .mha");
  if (!a.reference.empty() && a.spacing_given)
    return invalid_argument("give either --reference or --spacing, not both");
  return a;
}

Status convert(const ConvertArgs& a) {
  SOIQ_ASSIGN_OR_RETURN(TriangleMesh mesh, read_mesh(a.mesh, a.ras));
  const bool flipped = orient_outward(mesh);
  ImageGeometry grid;
  if (!a.reference.empty()) {
    SOIQ_ASSIGN_OR_RETURN(Image reference, read_image(a.reference));
    grid = reference.geometry;
  } else {
    SOIQ_ASSIGN_OR_RETURN(grid, grid_around(mesh, a.spacing_mm, a.margin));
  }
  VoxelizeOptions options;
  options.robust = a.robust;
  options.fill_rule = a.even_odd ? FillRule::kEvenOdd : FillRule::kNonZero;
  options.threads = a.threads;
  options.name = a.mesh.c_str();
  const auto t0 = std::chrono::steady_clock::now();
  SOIQ_ASSIGN_OR_RETURN(Voxelization v, voxelize_1d(mesh, grid, options));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  SOIQ_ASSIGN_OR_RETURN(Mask mask, to_mask(v.volume));
  SOIQ_RETURN_IF_ERROR(write_mask(mask, a.out));
  const int64_t n = voxel_count(v.volume);
  std::printf("%lld voxels inside, %.3f mm3 on %s; %s%s; %.2f ms%s -> %s\n", (long long)n,
              double(n) * grid.voxel_volume_mm3(), describe(grid).c_str(), describe(v.defects).c_str(),
              flipped ? ", orientation flipped to outward" : "", ms, a.robust ? " (robust)" : "", a.out.c_str());
  return ok_status();
}

}  // namespace

int run_convert_command(int argc, char** argv) { return run_command("convert", parse(argc, argv), convert); }

}  // namespace soiq::cli
