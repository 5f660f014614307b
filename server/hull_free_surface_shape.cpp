#include "server/hull_free_surface_shape.h"

#include <algorithm>

#include "core/mesh_defects.h"
#include "core/surface_shape.h"

namespace soiq::server {
namespace {

const std::vector<std::string> kHullFree = {
    "mesh_volume_mm3", "surface_area_mm2", "surface_volume_ratio",    "sphericity",
    "compactness_1",   "compactness_2",    "spherical_disproportion", "asphericity"};

const std::vector<std::string> kNeedHull = {"maximum_3d_diameter_mm", "volume_density_aabb", "area_density_aabb",
                                            "volume_density_convex_hull", "area_density_convex_hull"};

}  // namespace

bool needs_hull(const std::string& name) {
  return std::find(kNeedHull.begin(), kNeedHull.end(), name) != kNeedHull.end();
}

bool is_hull_free_surface_name(const std::string& name) {
  return std::find(kHullFree.begin(), kHullFree.end(), name) != kHullFree.end();
}

Result<std::vector<std::pair<std::string, double>>> hull_free_surface_shape(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return invalid_argument("surface shape of a mesh without triangles is undefined");
  const size_t nv = mesh.vertices_mm.size();
  // The same sum, in the same order, as surface_shape: equal values, bit for bit.
  double area = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (const int32_t v : tri) {
      if (v < 0 || size_t(v) >= nv)
        return invalid_argument("triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                                " outside [0, " + std::to_string(nv) + ")");
    }
    const Vec3& a = mesh.vertices_mm[size_t(tri[0])];
    area += norm(cross(mesh.vertices_mm[size_t(tri[1])] - a, mesh.vertices_mm[size_t(tri[2])] - a)) / 2;
  }
  const double volume = signed_volume_mm3(mesh);
  if (!(volume > 0)) {
    return invalid_argument("mesh encloses volume " + std::to_string(volume) +
                            " mm3 <= 0: it is inward-facing (use orient_outward) or not closed");
  }
  // No hull, no diameter, no box: only the values that do not depend on them are taken.
  const SurfaceShape s = surface_shape_from_measures(volume, area, ConvexHull{}, 0, Vec3{1, 1, 1});
  return std::vector<std::pair<std::string, double>>{{"mesh_volume_mm3", s.mesh_volume_mm3},
                                                     {"surface_area_mm2", s.surface_area_mm2},
                                                     {"surface_volume_ratio", s.surface_volume_ratio},
                                                     {"sphericity", s.sphericity},
                                                     {"compactness_1", s.compactness_1},
                                                     {"compactness_2", s.compactness_2},
                                                     {"spherical_disproportion", s.spherical_disproportion},
                                                     {"asphericity", s.asphericity}};
}

}  // namespace soiq::server
