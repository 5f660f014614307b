#include "client/cli/mesh_command.h"

#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "client/cli/cli_args.h"
#include "client/cli/exit_code.h"
#include "core/geometry/mesh_defects.h"
#include "core/io/marching_cubes.h"
#include "core/io/read_image.h"
#include "core/io/write_mesh.h"

namespace soiq::cli {
namespace {

struct MeshArgs {
  std::string mask_path;
  std::string out_path;
  int label = -1;  // < 0: every nonzero voxel
};

Result<MeshArgs> parse_args(int argc, char** argv) {
  MeshArgs args;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&](std::string_view name) -> Result<std::string> {
      if (i + 1 >= argc) return invalid_argument(std::string(name) + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(args.out_path, value(arg));
    } else if (arg == "--label" || arg.starts_with("--label=")) {
      std::string text;
      if (arg == "--label") {
        SOIQ_ASSIGN_OR_RETURN(text, value(arg));
      } else {
        text = std::string(arg.substr(8));
      }
      int label = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), label);
      if (ec != std::errc() || end != text.data() + text.size() || label < 0) {
        return invalid_argument("--label needs an integer >= 0, got '" + text + "'");
      }
      args.label = label;
    } else if (arg.starts_with("-") && arg.size() > 1) {
      return invalid_argument("unknown option '" + std::string(arg) + "'");
    } else if (args.mask_path.empty()) {
      args.mask_path = arg;
    } else {
      return invalid_argument("unexpected argument '" + std::string(arg) + "' (one MASK only)");
    }
  }
  if (args.mask_path.empty()) return invalid_argument("missing MASK");
  if (args.out_path.empty()) return invalid_argument("missing -o OUT");
  return args;
}

}  // namespace

Status mesh(const MeshArgs& args) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(args.out_path));
  SOIQ_ASSIGN_OR_RETURN(const Image image, read_image(args.mask_path));
  SOIQ_ASSIGN_OR_RETURN(const TriangleMesh surface, marching_cubes(mask_from_image(image, args.label)));
  if (surface.triangles.empty()) {
    const std::string which = args.label < 0 ? "nonzero voxels" : "voxels with label " + std::to_string(args.label);
    return invalid_argument("'" + args.mask_path + "' has no " + which + "; nothing to mesh");
  }
  SOIQ_RETURN_IF_ERROR(write_mesh(surface, args.out_path));
  std::printf("%zu triangles, %zu vertices, mesh volume %.3f mm3 -> %s\n", surface.triangles.size(),
              surface.vertices_mm.size(), signed_volume_mm3(surface), args.out_path.c_str());
  return ok_status();
}

int run_mesh_command(int argc, char** argv) { return run_command("mesh", parse_args(argc, argv), mesh); }

}  // namespace soiq::cli
