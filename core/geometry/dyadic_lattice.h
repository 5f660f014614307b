#pragma once
// Whether a point set lies on a small dyadic lattice: some power of two 2^k makes every coordinate
// an integer below 2^15 in magnitude. Marching-cubes and mask surfaces do (half-voxel lattice, in
// index units or in mm on grids of dyadic spacing and origin), and on such sets geometry can be
// exact and cheap: the plain double evaluation of a 3x3 orientation determinant of differences
// rounds nothing (scaled by 2^k, which changes no rounding, differences stay below 2^16, 2x2
// minors below 2^33, the determinant below 3 * 2^49: integers under 2^53), and integer keys
// replace sorting doubles.
//
// Input    points, any frame; non-finite coordinates make the answer "no".
// Output   k, the smallest such exponent (0 <= k <= 64), or nothing.
// Cost     O(n), no allocation. Thread-safe.

#include <optional>
#include <vector>

#include "core/base/vec3.h"

namespace soiq {

inline constexpr double kDyadicLatticeBound = 32768.0;  // 2^15

std::optional<int> dyadic_lattice_exponent(const std::vector<Vec3>& points);

}  // namespace soiq
