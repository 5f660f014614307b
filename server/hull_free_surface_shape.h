#pragma once
// The surface features of a stored surface that need no convex hull — mesh_volume_mm3,
// surface_area_mm2, surface_volume_ratio, sphericity, compactness_1, compactness_2,
// spherical_disproportion, asphericity — with the same sums and formulas as core/surface_shape
// (surface_shape_from_measures), so the values are bitwise those of structure_features.
//
// Why in server/: a query asking for sphericity alone otherwise pays structure_features'
// surface_shape, whose convex hull and diameter cost ~100x the volume and area on a near-convex
// surface of 10k-100k triangles (BENCHMARKS.md, "Query"). It goes once core's structure_features
// skips the hull when no hull feature is asked.
//
// hull_free_surface_shape: INVALID_ARGUMENT for a
// mesh without triangles, an index out of range, or a volume <= 0 (as surface_shape). O(T).

#include <string>
#include <utility>
#include <vector>

#include "core/status.h"
#include "core/triangle_mesh.h"

namespace soiq::server {

bool is_hull_free_surface_name(const std::string& name);
// The stored surface's features that do need it: maximum_3d_diameter_mm and the densities
// (convex hull; the bounding box along the grid axes stays with surface_shape too).
bool needs_hull(const std::string& name);

// name -> value for every hull-free surface feature.
Result<std::vector<std::pair<std::string, double>>> hull_free_surface_shape(const TriangleMesh& mesh);

}  // namespace soiq::server
