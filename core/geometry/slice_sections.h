#pragma once
// The sections of a closed surface by the slice planes of a grid: on each plane k = const of the
// grid's continuous index space, the closed polygons where the surface meets it (the planar
// contours an RT Structure Set holds, cut from a surface model).
//
// Inputs   mesh: closed and consistently oriented (mesh_defects(mesh).closed()), LPS mm.
//          geometry: the grid whose planes cut it (validate_geometry must pass); its slices
//          k = 0 .. dims[2] - 1 are the planes, any orientation.
// Output   For each slice k in ascending order, the polygons of the section, each a closed
//          polyline (the last point joins the first) of LPS points on plane k, oriented
//          counter-clockwise around the inside seen from +k in index space (holes clockwise).
//          Holes and separate parts are separate polygons. The rule, chosen so that even-odd
//          filling of the polygons gives exactly the 1D method's voxels (voxelize_1d.h):
//          vertices are mapped into index space as the 1D method maps them
//          (geometry.physical_to_lattice: the index space unless the slices are unevenly spaced,
//          then the planes lie at z = lattice_z(k)), and the plane is perturbed to k + d with d -> 0+ and d
//          infinitesimal against the rows' perturbation y = j + e of fill_contours.h (d = e^2,
//          the 1D method's (j + e, k + e^2)). So a vertex with z <= k is below the plane and one
//          with z > k above (a comparison of the same doubles the 1D method compares: exact), a
//          face lying in the plane is not cut, and an edge in the plane is cut once, by the face
//          that rises from it. Where an edge crosses, the point is interpolated from its lower
//          end (the same point for both faces sharing the edge; exactly the vertex when it lies
//          in the plane). Then, on slice k, a voxel centre is inside the surface (1D method,
//          even-odd) iff it is inside an odd number of the polygons, with fill_contours' rule
//          for centres on an edge, up to the rounding of the interpolated points (a centre
//          within ~1e-15 of the surface may fall on either side).
//          Polygons of zero area, which change no voxel under even-odd (the plane touching the
//          surface along an edge or at a vertex), are left out: repeated consecutive points are
//          merged, and a polygon with fewer than 3 points left, or whose points are all
//          collinear (exact orient2d in index space), is dropped.
// Errors   INVALID_ARGUMENT: invalid geometry, or a mesh validate_mesh refuses (empty, non-finite,
//          bad indices). FAILED_PRECONDITION: the mesh is not closed and consistently oriented
//          (message names `name` and its defects).
// Cost     O(T + C log C) for T triangles and C cuts (a triangle spanning s slices is cut s
//          times); memory O(C). Thread-safe.
// Caveats  A surface that intersects itself yields polygons that cross; even-odd then counts
//          overlaps as outside, as the 1D method's even-odd rule does (its default nonzero rule
//          does not). Collinear points along an edge are kept: the polygons follow the surface's
//          edges exactly, not simplified.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"

namespace soiq {

struct SliceSection {
  int64_t slice = 0;            // k, in [0, dims[2])
  std::vector<Vec3> points_mm;  // LPS, on plane k, >= 3 points, closed
};

Result<std::vector<SliceSection>> slice_sections(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                                 const std::string& name = "mesh");

}  // namespace soiq
