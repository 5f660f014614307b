#include "core/features/mask_maximum_2d_diameters.h"

#include <algorithm>

namespace soiq {
namespace {

double family_diameter(const PlaneFamily& f, const Vec3& spacing) {
  // Doubled coordinates: half a spacing per unit.
  const double su = 0.5 * spacing[size_t(f.row_axis)], sv = 0.5 * spacing[size_t(f.value_axis)];
  double best = 0;
  for (const auto& hull : f.hulls) best = std::max(best, lattice_polygon_diameter(hull, su, sv));
  return best;
}

}  // namespace

Result<Maximum2DDiameters> mask_maximum_2d_diameters(const MaskSurfaceSweep& sweep, const Vec3& spacing_mm) {
  if (sweep.empty) return invalid_argument("maximum 2D diameters of an empty mask are undefined");
  Maximum2DDiameters out;
  out.row_mm = family_diameter(sweep.families[0], spacing_mm);
  out.column_mm = family_diameter(sweep.families[1], spacing_mm);
  out.slice_mm = family_diameter(sweep.families[2], spacing_mm);
  return out;
}

}  // namespace soiq
