#include "client/cli/mesh_on_grid.h"

#include <chrono>

#include "client/cli/cli_args.h"
#include "core/grid_around.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"

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

Result<MeshOnGrid> convert_mesh_file(const std::string& path, const MeshGridOptions& o) {
  MeshOnGrid out;
  SOIQ_ASSIGN_OR_RETURN(out.mesh, read_mesh(path, o.ras));
  out.flipped = orient_outward(out.mesh);
  if (!o.reference.empty()) {
    SOIQ_ASSIGN_OR_RETURN(Image reference, read_image(o.reference));
    out.grid = reference.geometry;
  } else {
    SOIQ_ASSIGN_OR_RETURN(out.grid, grid_around(out.mesh, o.spacing_mm, o.margin));
  }
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
