#pragma once
// The common front of the reference methods (core/reference/): checks a mesh and a grid and maps
// every vertex into the grid's continuous index space, u = (D S)^-1 (p - origin), where voxel
// centres sit at integer points (docs/DESIGN.md "The 1D method, precisely", step 1). Deliberately
// independent of voxelize_1d so the references stay an oracle for it.
//
// Inputs   mesh in LPS mm; geometry a grid (any direction matrix).
// Output   one index-space point per vertex, in vertex order.
// Errors   INVALID_ARGUMENT  invalid geometry, no triangles, a non-finite vertex, an index outside
//                            [0, vertex count);
//          RESOURCE_EXHAUSTED the grid has more than kDefaultMaxVoxels voxels.
// Cost     O(V + T); thread-safe.

#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"

namespace soiq {

Result<std::vector<Vec3>> index_space_vertices(const TriangleMesh& mesh, const ImageGeometry& geometry);

}  // namespace soiq
