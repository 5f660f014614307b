#pragma once
// The 1D scanline method: a closed surface model -> its volume model (docs/DESIGN.md, "The 1D method,
// precisely"; the paper's 1D method, made exact and watertight).
//
// Inputs
//   mesh      triangles in LPS mm; any orientation of the grid (direction matrix) is fine.
//   geometry  the target grid (validate_geometry must pass).
//   options   fill rule (nonzero by default), robust three-axis vote, thread count.
// Output
//   A RunLengthVolume on `geometry`: voxel (i,j,k) is inside iff its centre is inside the surface.
//   Each row line (j,k) is intersected with every triangle whose (y,z) projection (in continuous
//   index space) contains the point (j,k). The point is perturbed symbolically to
//   (j + e, k + e^2), e -> 0+, so a line through a shared edge or vertex is counted by exactly one
//   of the triangles sharing it, with no epsilon: every line crosses a closed mesh an even number
//   of times, whatever the grid alignment. A centre exactly on an entering crossing is inside, on a
//   leaving crossing is not (runs are half-open). Every such decision is exact for the mesh's
//   vertices as mapped into index space (geometry.physical_to_index): signs come from filtered
//   predicates with an exact fallback (core/geometry/exact_predicates.h), never from rounding.
// Errors
//   INVALID_ARGUMENT   bad geometry, empty mesh, non-finite vertices, indices out of range.
//   FAILED_PRECONDITION plain mode on a mesh that is not closed and consistently oriented
//                      (message names robust mode).
//   RESOURCE_EXHAUSTED  grid over options.max_voxels (checked before allocating).
// Cost
//   O(T + crossings + lines): each triangle is visited once, on one thread; memory
//   O(crossings + runs + lines). Robust mode materialises three dense votes: O(voxels).
//   Thread-safe; results are identical for any thread count.
// Caveats
//   Robust mode treats a line whose crossings do not balance as voting "outside" everywhere.
//   Exactness assumes products of index-space coordinates neither overflow nor underflow.

#include <cstdint>
#include <optional>

#include "core/base/fill_rule.h"
#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/geometry/mesh_defects.h"

namespace soiq {

struct VoxelizeOptions {
  FillRule fill_rule = FillRule::kNonZero;
  bool robust = false;  // three-axis 2-of-3 vote for meshes with holes or cracks
  int threads = 1;      // >= 1
  int64_t max_voxels = kDefaultMaxVoxels;
  const char* name = "mesh";  // used in error messages
  // The mesh's defects when the caller already has them (the store computes them once at upload,
  // a benchmark once at load); otherwise voxelize_1d computes them, O(T log d) for degree d.
  std::optional<MeshDefects> known_defects;
};

struct Voxelization {
  RunLengthVolume volume;
  MeshDefects defects;
};

Result<Voxelization> voxelize_1d(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                 const VoxelizeOptions& options = {});

}  // namespace soiq
