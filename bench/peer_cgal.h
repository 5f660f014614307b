#pragma once
// CGAL as a benchmark peer: CGAL::Side_of_triangle_mesh (Epick kernel) asked about every voxel
// centre of the grid, inside (or on the surface) 1, outside 0. The mesh goes in as a
// CGAL::Surface_mesh in LPS mm, and its AABB tree is built once, untimed; the timed region is the
// mask's allocation and one query per voxel centre (index_to_physical, then a ray cast through
// the tree). Single-threaded. Only in builds with CGAL (SOIQ_HAVE_CGAL); otherwise prepare_cgal
// returns UNIMPLEMENTED.

#include "bench/conversion.h"

namespace soiq::bench {

bool cgal_available();
Result<Conversion> prepare_cgal(const TriangleMesh& mesh, const ImageGeometry& geometry);

}  // namespace soiq::bench
