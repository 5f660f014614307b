#include "core/io/geometry_from_axes.h"

#include <cmath>

namespace soiq {

Result<ImageGeometry> geometry_from_axes(const Mat3& axes_mm, const Vec3& origin_mm, const std::array<int64_t, 3>& dims,
                                         const std::string& name) {
  ImageGeometry g;
  g.origin_mm = origin_mm;
  g.dims = dims;
  for (int c = 0; c < 3; ++c) {
    const Vec3 axis{axes_mm[0][c], axes_mm[1][c], axes_mm[2][c]};
    const double length = norm(axis);
    if (!std::isfinite(length) || !(length > 0)) {
      return invalid_argument("image '" + name + "' has a zero or non-finite voxel axis " + std::to_string(c) +
                              " in its header");
    }
    g.spacing_mm[c] = length;
    for (int r = 0; r < 3; ++r) g.direction[r][c] = axis[r] / length;
  }
  const Status valid = validate_geometry(g);
  if (!valid.ok()) {
    return invalid_argument("image '" + name +
                            "' has sheared or non-orthogonal axes that soiq does not support (rows and columns must "
                            "be at right angles, slices within 60 degrees of their normal): " +
                            valid.message());
  }
  return g;
}

}  // namespace soiq
