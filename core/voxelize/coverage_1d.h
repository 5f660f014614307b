#pragma once
// Coverage fractions by the 1D method (docs/DESIGN.md, "Coverage fractions"): the fraction of each
// voxel's volume inside a closed surface, exact along the row axis and sampled on n x n lines
// across it, in one pass of the same lattice walk as voxelize_1d (no n-times-finer grid is ever
// held: one slice of sample lines at a time).
//
// Inputs
//   mesh      triangles in LPS mm, closed and consistently oriented (no robust mode: a fraction
//             needs an inside that every line agrees on).
//   geometry  the target grid (validate_geometry must pass).
//   options   n = lines_per_voxel in [1, 8], fill rule, threads, max_voxels, name.
// Output
//   A CoverageVolume on `geometry`. Voxel (i,j,k)'s fraction is the mean, over the n x n lines
//   through the centres of an n x n split of its (j,k) cross-section, of the length of the line's
//   segment [i - 1/2, i + 1/2) inside the surface. Which lines cross which triangles is decided
//   exactly, as in voxelize_1d (scan_lattice.h); crossing positions are interpolated in double.
//   A voxel the surface does not enter is exactly 1 inside and exactly 0 outside.
// Error
//   The sum of fractions times the voxel volume differs from the surface's volume by at most the
//   volume of the points within r = (1/2n) sqrt(sy^2 + sz^2) mm (sy, sz the spacings across the
//   rows) of the surface: a point is counted wrongly only when its sample line's point in the same
//   row is on the other side, and the two are at most r apart. For a convex body of surface area A
//   inside a ball of radius R that volume is at most 2 r A + 4 pi R r^2 + (4/3) pi r^3 (Steiner).
//   The error of smooth surfaces is far smaller in practice (second order in 1/n away from where
//   the surface is tangent to the rows).
// Errors
//   INVALID_ARGUMENT   bad geometry, empty mesh, non-finite vertices, n outside [1, 8].
//   FAILED_PRECONDITION a mesh that is not closed and consistently oriented.
//   RESOURCE_EXHAUSTED  grid over options.max_voxels, or n^2 times the grid's lines over 2^31.
// Cost
//   O(T + n^2 (crossings + lines)): every triangle visits the n x n lattice of lines it spans;
//   memory O(output + one slice's crossings). Thread-safe; identical results for any thread count.

#include <optional>

#include "core/base/coverage_volume.h"
#include "core/base/fill_rule.h"
#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/geometry/mesh_defects.h"

namespace soiq {

inline constexpr int kMaxLinesPerVoxel = 8;

struct CoverageOptions {
  int lines_per_voxel = 4;  // n: n x n sample lines across each voxel
  FillRule fill_rule = FillRule::kNonZero;
  int threads = 1;
  int64_t max_voxels = kDefaultMaxVoxels;
  const char* name = "mesh";
  std::optional<MeshDefects> known_defects;
};

Result<CoverageVolume> coverage_1d(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                   const CoverageOptions& options = {});

}  // namespace soiq
