// `soiq`: the command-line client. Each command lives in its own <name>_command.cpp.
#include <cstdio>
#include <cstring>
#include <string>

#include "client/cli/compare_command.h"
#include "client/cli/convert_command.h"
#include "client/cli/features_command.h"
#include "client/cli/mesh_command.h"

namespace {

constexpr const char* kHelp =
    "soiq - query medical images by the content of their structures of interest\n"
    "\n"
    "Offline commands (no server needed):\n"
    "  soiq convert MESH -o OUT.{nii.gz,nii,nrrd,mha} [--reference IMAGE | --spacing S|SX,SY,SZ [--margin N]]\n"
    "               [--robust] [--even-odd] [--threads N] [--ras]\n"
    "      surface model -> volume model (the 1D scanline method); prints one summary line\n"
    "  soiq mesh MASK -o OUT.{stl,vtk,vtp,ply,obj} [--label N]\n"
    "      mask -> surface model (marching cubes at 0.5, LPS mm, outward normals)\n"
    "  soiq features INPUT [--label N] [--reference IMAGE | --spacing S [--margin N]] [--image [NAME=]IMAGE]...\n"
    "               [--region inside|shell:R|core:R]... [--features LIST] [--format table|json|csv]\n"
    "               [--interpolation nearest|linear] [--ibsi] [--robust] [--even-odd] [--ras] [--threads N]\n"
    "      shape and intensity features of a structure (a surface model or a mask)\n"
    "  soiq compare MASK_A MASK_B [--label-a N] [--label-b N]\n"
    "      overlap of two masks on one grid: IoU, Dice, differing voxels\n"
    "\n"
    "Exit codes: 0 ok, 1 other, 2 invalid argument or usage, 3 not found, 4 failed precondition,\n"
    "5 resource exhausted.\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::fputs(kHelp, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  if (command == "convert") return soiq::cli::run_convert_command(argc - 1, argv + 1);
  if (command == "features") return soiq::cli::run_features_command(argc - 1, argv + 1);
  if (command == "compare") return soiq::cli::run_compare_command(argc - 1, argv + 1);
  if (command == "mesh") return soiq::cli::run_mesh_command(argc - 1, argv + 1);
  std::fprintf(stderr, "soiq: unknown command '%s' (try 'soiq help')\n", command.c_str());
  return 2;
}
