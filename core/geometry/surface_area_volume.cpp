#include "core/geometry/surface_area_volume.h"

#include <cmath>
#include <string>

namespace soiq {

Result<SurfaceAreaVolume> surface_area_volume(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return invalid_argument("surface shape of a mesh without triangles is undefined");
  const size_t nv = mesh.vertices_mm.size();
  SurfaceAreaVolume out;
  out.used.assign(nv, 0);
  // Area and volume from one normal per triangle: det(a - o, b - o, c - o) = (a - o) . n.
  const Vec3 o = mesh.vertices_mm.empty() ? Vec3{0, 0, 0} : mesh.vertices_mm[0];
  double twice_area = 0, six_volume = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const int32_t v : mesh.triangles[t]) {
      if (v < 0 || size_t(v) >= nv) {
        return invalid_argument("triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                                " outside [0, " + std::to_string(nv) + ")");
      }
      out.used[size_t(v)] = 1;
    }
    const auto& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices_mm[size_t(tri[0])];
    const Vec3 n = cross(mesh.vertices_mm[size_t(tri[1])] - a, mesh.vertices_mm[size_t(tri[2])] - a);
    twice_area += norm(n);
    six_volume += dot(a - o, n);
  }
  out.area_mm2 = twice_area / 2;
  out.volume_mm3 = six_volume / 6;
  if (!std::isfinite(out.area_mm2) || !std::isfinite(out.volume_mm3)) {  // name the culprit
    for (size_t v = 0; v < nv; ++v) {
      const Vec3& p = mesh.vertices_mm[v];
      if (out.used[v] && !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) {
        return invalid_argument("mesh vertex " + std::to_string(v) + " has a non-finite coordinate");
      }
    }
  }
  if (!(out.volume_mm3 > 0)) {
    return invalid_argument("mesh encloses volume " + std::to_string(out.volume_mm3) +
                            " mm3 <= 0: it is inward-facing (use orient_outward) or not closed");
  }
  return out;
}

}  // namespace soiq
