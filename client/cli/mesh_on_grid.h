#pragma once
// What the commands that take a surface model share: its options (the target grid — --reference
// IMAGE, or --spacing S|SX,SY,SZ with --margin N — and the 1D method's --robust, --even-odd,
// --threads, --ras) and the conversion itself: read, orient outward, build the grid, voxelize.

#include <functional>
#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::cli {

struct MeshGridOptions {
  std::string reference;
  Vec3 spacing_mm{1, 1, 1};
  bool spacing_given = false;
  int margin = 2;
  bool robust = false, even_odd = false, ras = false;
  int threads = 1;
};

// When argv[i] is one of the options above, consumes it (and its value, advancing i) and returns
// true; false when it is not one of them. INVALID_ARGUMENT for a missing or bad value.
Result<bool> parse_mesh_grid_option(int argc, char** argv, int& i, MeshGridOptions& options);

// INVALID_ARGUMENT when the options contradict each other (--reference with --spacing).
Status check_mesh_grid_options(const MeshGridOptions& options);

struct MeshOnGrid {
  TriangleMesh mesh;     // LPS, outward
  bool flipped = false;  // the file's orientation was inward and has been flipped
  ImageGeometry grid;
  Voxelization voxels;
  double milliseconds = 0;  // of the 1D method alone
};

// Reads `path`, orients it outward and builds the grid, refusing (RESOURCE_EXHAUSTED, in one line)
// work whose `needed_bytes` exceed the offline memory budget (SOIQ_MEMORY_BUDGET, or half the
// machine's memory). `voxels` stays empty.
using NeededBytes = std::function<int64_t(const TriangleMesh&, const ImageGeometry&)>;
Result<MeshOnGrid> read_mesh_on_grid(const std::string& path, const MeshGridOptions& options,
                                     const NeededBytes& needed_bytes);

// read_mesh_on_grid, then the mesh converted with the 1D method.
Result<MeshOnGrid> convert_mesh_file(const std::string& path, const MeshGridOptions& options);

}  // namespace soiq::cli
