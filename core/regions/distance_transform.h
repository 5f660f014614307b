#pragma once
// The exact squared Euclidean distance transform of a dense box of voxels, in mm² (docs/DESIGN.md
// "Features", regions): for every voxel centre, the squared distance to the nearest source voxel
// centre. Separable, one pass per
// axis, each pass the lower envelope of parabolas of Felzenszwalb & Huttenlocher, "Distance Transforms of Sampled
// Functions", Theory of Computing 8 (2012), with the spacing of each axis folded into the parabolas, so anisotropic
// grids give distances in mm.
//
// Inputs
//   sources     dims[0]*dims[1]*dims[2] bytes, i fastest (index = i + nx * (j + ny * k)); nonzero
//               marks a source voxel.
//   dims        nx, ny, nz >= 0 of the box.
//   spacing_mm  voxel spacing along i, j, k; finite and > 0. The box axes are taken as orthogonal
//               (true of every ImageGeometry: its direction matrix is orthonormal).
//   threads     >= 1; lines of each pass are split among them.
// Output
//   One double per voxel: the exact squared distance in mm² (up to the rounding of a few double
//   operations) to the nearest source; +infinity everywhere when there is no source.
// Errors
//   INVALID_ARGUMENT  sources.size() != nx*ny*nz, dims < 0, spacing not finite or <= 0.
// Cost
//   O(voxels) time, 8 bytes per voxel for the output plus O(max(nx,ny,nz)) scratch per
//   thread. Thread-safe; the result does not depend on the thread count.
// Caveats
//   Distances are between voxel centres only; sources outside the box do not exist for it.

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq {

Result<std::vector<double>> squared_distance_transform(const std::vector<uint8_t>& sources,
                                                       const std::array<int64_t, 3>& dims, const Vec3& spacing_mm,
                                                       int threads = 1);

}  // namespace soiq
