#include "core/centre_of_mass_shift.h"

#include <cmath>
#include <string>

namespace soiq {

Result<double> centre_of_mass_shift_mm(const RunLengthVolume& region, const Image& image) {
  const ImageGeometry& g = region.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  SOIQ_RETURN_IF_ERROR(check_same_grid(g, image.geometry));
  if (image.voxels.size() != size_t(image.geometry.voxel_count())) {
    return invalid_argument("image has " + std::to_string(image.voxels.size()) + " voxels but its grid is " +
                            describe(image.geometry));
  }
  const int64_t lines = region.line_count();
  if (int64_t(region.line_start.size()) != lines + 1 || region.line_start.back() != int64_t(region.runs.size())) {
    return invalid_argument("region's run table does not match its grid " + describe(g));
  }
  // Sums in index space: integer coordinates add up exactly in double (below 2^53), so only the
  // weighted sums round; both centroids are mapped to LPS at the end.
  const int64_t nx = g.dims[0], ny = g.dims[1];
  double n = 0, w = 0;
  Vec3 s{0, 0, 0}, sw{0, 0, 0};
  for (int64_t l = 0; l < lines; ++l) {
    const int64_t j = l % ny, k = l / ny;
    const float* row = image.voxels.data() + nx * l;
    for (int64_t r = region.line_start[l]; r < region.line_start[l + 1]; ++r) {
      if (region.runs[r].begin < 0 || region.runs[r].end > nx) {
        return invalid_argument("region has a run outside its grid " + describe(g));
      }
      for (int64_t i = region.runs[r].begin; i < region.runs[r].end; ++i) {
        const double v = row[i];
        if (!std::isfinite(v)) {
          return invalid_argument("image value at voxel (" + std::to_string(i) + ", " + std::to_string(j) + ", " +
                                  std::to_string(k) + ") inside the region is not finite");
        }
        n += 1, w += v;
        s = s + Vec3{double(i), double(j), double(k)};
        sw = sw + v * Vec3{double(i), double(j), double(k)};
      }
    }
  }
  if (n == 0) return invalid_argument("centre of mass shift of an empty region is undefined");
  if (w == 0) return invalid_argument("image values inside the region sum to 0: no intensity-weighted centroid");
  const Vec3 geometric = g.index_to_physical((1 / n) * s);
  const Vec3 weighted = g.index_to_physical((1 / w) * sw);
  return norm(geometric - weighted);
}

}  // namespace soiq
