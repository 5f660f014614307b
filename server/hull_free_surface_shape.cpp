#include "server/hull_free_surface_shape.h"

#include <algorithm>

#include "core/surface_area_volume.h"
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
  // surface_shape's own pass (surface_area_volume.h): equal values, bit for bit.
  SOIQ_ASSIGN_OR_RETURN(const SurfaceAreaVolume measures, surface_area_volume(mesh));
  const double volume = measures.volume_mm3, area = measures.area_mm2;
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
