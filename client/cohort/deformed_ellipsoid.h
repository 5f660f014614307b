#pragma once
// A closed surface shaped like a deep-brain structure: an ellipsoid whose radius is modulated by a
// smooth low-frequency bump, meshed as a UV sphere of about `triangles` triangles.
//
// Inputs: the ellipsoid (centre and semi-axes in LPS mm, semi-axes > 0); the bump
//   r(theta, phi) = 1 + sum_k amplitude[k] * sin(order[k] * theta + phase[k]) * cos((k + 1) * phi + phase[k])
//   over the unit sphere's polar angle theta and azimuth phi; the amplitudes must sum to < 1, and
//   draw_radial_bump keeps them below 0.24, so r stays in (0.76, 1.24); triangles >= 8.
// Output: the UV sphere of core/geometry/primitives.h (uv_sphere_with_triangles) with each vertex v
//   moved to centre + r(v) * semi_axes * v (per axis). Moving vertices along their own ray by a
//   positive factor and scaling the axes keeps the mesh star-shaped: closed, outward, manifold, with
//   no self-intersection.
// draw_radial_bump: 4 terms, amplitude in [0, 0.06), phase in [0, 6.28), order 1-3 each, drawn in
//   that order per term (12 draws).
// Cost: O(triangles). Thread-safe.

#include <array>
#include <cstdint>

#include "client/cohort/split_mix_64.h"
#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"

namespace soiq::cohort {

struct Ellipsoid {
  Vec3 centre_mm{};
  Vec3 semi_axes_mm{};
};

struct RadialBump {
  std::array<double, 4> amplitude{}, phase{};
  std::array<int, 4> order{1, 1, 1, 1};
};

RadialBump draw_radial_bump(SplitMix64& random);

TriangleMesh deformed_ellipsoid(const Ellipsoid& ellipsoid, const RadialBump& bump, int64_t triangles);

}  // namespace soiq::cohort
