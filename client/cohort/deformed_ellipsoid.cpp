#include "client/cohort/deformed_ellipsoid.h"

#include <cmath>

#include "core/geometry/primitives.h"

namespace soiq::cohort {

RadialBump draw_radial_bump(SplitMix64& random) {
  RadialBump bump;
  for (size_t k = 0; k < bump.amplitude.size(); ++k) {
    bump.amplitude[k] = random.uniform(0.0, 0.06);
    bump.phase[k] = random.uniform(0, 6.28);
    bump.order[k] = random.integer(1, 3);
  }
  return bump;
}

TriangleMesh deformed_ellipsoid(const Ellipsoid& e, const RadialBump& bump, int64_t triangles) {
  TriangleMesh m = uv_sphere_with_triangles({0, 0, 0}, 1.0, triangles);
  for (Vec3& v : m.vertices_mm) {
    // Clamped: a pole's z can round to just over 1, and acos would give NaN.
    const double theta = std::acos(std::fmax(-1.0, std::fmin(1.0, v[2])));
    const double phi = std::atan2(v[1], v[0]);
    double r = 1;
    for (size_t k = 0; k < bump.amplitude.size(); ++k)
      r += bump.amplitude[k] * std::sin(bump.order[k] * theta + bump.phase[k]) *
           std::cos(double(k + 1) * phi + bump.phase[k]);
    for (int a = 0; a < 3; ++a) v[a] = e.centre_mm[a] + r * e.semi_axes_mm[a] * v[a];
  }
  return m;
}

}  // namespace soiq::cohort
