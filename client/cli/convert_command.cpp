#include "client/cli/convert_command.h"

#include <chrono>
#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/exit_code.h"
#include "client/cli/fraction_args.h"
#include "client/cli/mesh_on_grid.h"
#include "client/cli/structure_operand.h"
#include "core/io/write_image.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/memory_estimate.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::cli {

namespace {

struct ConvertArgs {
  std::string mesh, out;
  MeshGridOptions grid;
  FractionArgs fractions;
};

Result<ConvertArgs> parse_convert_args(int argc, char** argv) {
  ConvertArgs a;
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool shared, parse_mesh_grid_option(argc, argv, i, a.grid));
    if (shared) continue;
    SOIQ_ASSIGN_OR_RETURN(const bool fraction_option, parse_fraction_option(argc, argv, i, a.fractions));
    if (fraction_option) continue;
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
  SOIQ_RETURN_IF_ERROR(check_fraction_args(a.fractions));
  if (a.fractions.fractional && a.grid.robust) {
    return invalid_argument("--fractional needs a closed surface; --robust (for open ones) cannot give fractions");
  }
  return a;
}

// The fractions of each voxel inside the surface (coverage_1d), written as bytes 0-255 or floats.
Status convert_fractions(const ConvertArgs& a) {
  const int n = a.fractions.lines_per_voxel();
  SOIQ_ASSIGN_OR_RETURN(const MeshOnGrid m,
                        read_mesh_on_grid(a.mesh, a.grid, [&](const TriangleMesh& mesh, const ImageGeometry& grid) {
                          return coverage_peak_bytes(surface_measure(mesh), grid, n).bytes +
                                 fraction_export_extra_bytes(grid, a.fractions.float32 ? 4 : 1);
                        }));
  CoverageOptions options;
  options.lines_per_voxel = n;
  options.fill_rule = a.grid.even_odd ? FillRule::kEvenOdd : FillRule::kNonZero;
  options.threads = a.grid.threads;
  options.name = a.mesh.c_str();
  const auto t0 = std::chrono::steady_clock::now();
  SOIQ_ASSIGN_OR_RETURN(const CoverageVolume v, coverage_1d(m.mesh, m.grid, options));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (a.fractions.float32) {
    SOIQ_ASSIGN_OR_RETURN(const Image image, to_fraction_image(v));
    SOIQ_RETURN_IF_ERROR(write_image(image, a.out));
  } else {
    SOIQ_ASSIGN_OR_RETURN(const Mask bytes, to_fraction_bytes(v));
    SOIQ_RETURN_IF_ERROR(write_mask(bytes, a.out));
  }
  const int64_t touched = voxel_count(any_coverage(v));
  std::printf(
      "%lld voxels inside or partly (%zu partly), %.3f mm3 by fractions (%dx%d lines per voxel) on %s%s; %.2f "
      "ms -> %s (%s)\n",
      (long long)touched, v.partial.size(), covered_voxels(v) * m.grid.voxel_volume_mm3(), n, n,
      describe(m.grid).c_str(), m.flipped ? ", orientation flipped to outward" : "", ms, a.out.c_str(),
      a.fractions.float32 ? "float32 0-1" : "uint8 0-255");
  return ok_status();
}

Status convert(const ConvertArgs& a) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  if (a.fractions.fractional) return convert_fractions(a);
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
