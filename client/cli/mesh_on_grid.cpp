#include "client/cli/mesh_on_grid.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>

#include "client/cli/cli_args.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/memory_estimate.h"

namespace soiq::cli {

Result<bool> parse_mesh_grid_option(int argc, char** argv, int& i, MeshGridOptions& o) {
  const std::string arg = argv[i];
  auto value = [&]() -> Result<std::string> {
    if (i + 1 >= argc) return invalid_argument(arg + " needs a value");
    return std::string(argv[++i]);
  };
  if (arg == "--reference") {
    SOIQ_ASSIGN_OR_RETURN(o.reference, value());
  } else if (arg == "--spacing") {
    SOIQ_ASSIGN_OR_RETURN(std::string text, value());
    SOIQ_ASSIGN_OR_RETURN(o.spacing_mm, parse_spacing(text));
    o.spacing_given = true;
  } else if (arg == "--margin") {
    SOIQ_ASSIGN_OR_RETURN(std::string text, value());
    SOIQ_ASSIGN_OR_RETURN(o.margin, parse_int(text, "--margin", 0, 1000000));
  } else if (arg == "--threads") {
    SOIQ_ASSIGN_OR_RETURN(std::string text, value());
    SOIQ_ASSIGN_OR_RETURN(o.threads, parse_int(text, "--threads", 1, 1024));
  } else if (arg == "--robust") {
    o.robust = true;
  } else if (arg == "--even-odd") {
    o.even_odd = true;
  } else if (arg == "--ras") {
    o.ras = true;
  } else {
    return false;
  }
  return true;
}

Status check_mesh_grid_options(const MeshGridOptions& o) {
  if (!o.reference.empty() && o.spacing_given)
    return invalid_argument("give either --reference or --spacing, not both");
  return ok_status();
}

Result<int64_t> offline_memory_budget() {
  const char* text = std::getenv("SOIQ_MEMORY_BUDGET");
  if (!text || !*text) return default_memory_budget_bytes();
  return parse_byte_size(text, "environment variable SOIQ_MEMORY_BUDGET");
}

Result<MeshOnGrid> read_mesh_on_grid(const std::string& path, const MeshGridOptions& o,
                                     const NeededBytes& needed_bytes) {
  MeshOnGrid out;
  SOIQ_ASSIGN_OR_RETURN(out.mesh, read_mesh(path, o.ras));
  out.flipped = orient_outward(out.mesh);
  if (!o.reference.empty()) {
    SOIQ_ASSIGN_OR_RETURN(Image reference, read_image(o.reference));
    out.grid = reference.geometry;
  } else {
    SOIQ_ASSIGN_OR_RETURN(out.grid, grid_around(out.mesh, o.spacing_mm, o.margin));
  }
  // The same estimate soiqd admits work by: a mesh that would need more than this machine can give
  // is refused here, in one line, instead of dying of bad_alloc (or the OOM killer) minutes later.
  SOIQ_RETURN_IF_ERROR(check_grid_size(out.grid, kDefaultMaxVoxels));
  SOIQ_ASSIGN_OR_RETURN(const int64_t budget, offline_memory_budget());
  const int64_t needed = needed_bytes(out.mesh, out.grid);
  if (needed > budget) {
    const auto& d = out.grid.dims;
    return resource_exhausted("'" + path + "' on a grid of " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
                              std::to_string(d[2]) + " voxels (" + std::to_string(d[1] * d[2]) +
                              " row lines) needs an estimated " + human_bytes(needed) +
                              ", more than the memory budget of " + human_bytes(budget) +
                              " (half this machine's memory; SOIQ_MEMORY_BUDGET sets it): use a coarser --spacing or a "
                              "smaller --margin");
  }
  return out;
}

Result<MeshOnGrid> convert_mesh_file(const std::string& path, const MeshGridOptions& o) {
  SOIQ_ASSIGN_OR_RETURN(
      MeshOnGrid out, read_mesh_on_grid(path, o, [&](const TriangleMesh& mesh, const ImageGeometry& grid) {
        const ConversionEstimate estimate = conversion_peak_bytes(mesh, grid, o.robust);
        return estimate.bytes + std::max(features_extra_bytes(estimate, grid, 0, 0), mask_export_extra_bytes(grid));
      }));
  VoxelizeOptions options;
  options.robust = o.robust;
  options.fill_rule = o.even_odd ? FillRule::kEvenOdd : FillRule::kNonZero;
  options.threads = o.threads;
  options.name = path.c_str();
  const auto t0 = std::chrono::steady_clock::now();
  SOIQ_ASSIGN_OR_RETURN(out.voxels, voxelize_1d(out.mesh, out.grid, options));
  out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace soiq::cli
