#include "core/features/mask_maximum_2d_diameters.h"

#include <algorithm>

namespace soiq {
namespace {

double family_diameter(const PlaneFamily& f, const ImageGeometry& grid) {
  // Doubled coordinates: half a spacing per unit.
  const Vec3& spacing = grid.spacing_mm;
  const size_t u = size_t(f.row_axis), v = size_t(f.value_axis);
  double best = 0;
  if (!grid.sheared()) {
    for (const auto& hull : f.hulls)
      best = std::max(best, lattice_polygon_diameter(hull, 0.5 * spacing[u], 0.5 * spacing[v]));
    return best;
  }
  const Mat3& d = grid.direction;
  const Vec3 step_u = (0.5 * spacing[u]) * Vec3{d[0][u], d[1][u], d[2][u]};
  const Vec3 step_v = (0.5 * spacing[v]) * Vec3{d[0][v], d[1][v], d[2][v]};
  for (const auto& hull : f.hulls) best = std::max(best, lattice_polygon_diameter(hull, step_u, step_v));
  return best;
}

}  // namespace

Result<Maximum2DDiameters> mask_maximum_2d_diameters(const MaskSurfaceSweep& sweep, const ImageGeometry& grid) {
  if (sweep.empty) return invalid_argument("maximum 2D diameters of an empty mask are undefined");
  Maximum2DDiameters out;
  out.row_mm = family_diameter(sweep.families[0], grid);
  out.column_mm = family_diameter(sweep.families[1], grid);
  out.slice_mm = family_diameter(sweep.families[2], grid);
  return out;
}

}  // namespace soiq
