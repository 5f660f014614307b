#include "core/features/centre_of_mass_shift.h"

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
      // Per run: sum v and sum v i in four partial sums each (one chain of dependent additions
      // would bound the loop by the adder's latency); the unweighted sums in closed form.
      const int64_t b = region.runs[r].begin, e = region.runs[r].end;
      double rv[4] = {0, 0, 0, 0}, rvi[4] = {0, 0, 0, 0};
      int64_t i = b;
      for (; i + 4 <= e; i += 4) {
        for (int q = 0; q < 4; ++q) rv[q] += row[i + q], rvi[q] += double(row[i + q]) * double(i + q);
      }
      for (; i < e; ++i) rv[0] += row[i], rvi[0] += double(row[i]) * double(i);
      const double run_w = (rv[0] + rv[1]) + (rv[2] + rv[3]), run_wi = (rvi[0] + rvi[1]) + (rvi[2] + rvi[3]);
      // A float times an index below 2^31 cannot overflow a double: a non-finite sum means a
      // non-finite value, named here.
      if (!std::isfinite(run_w) || !std::isfinite(run_wi)) {
        for (i = b; i + 1 < e && std::isfinite(row[i]);) ++i;
        return invalid_argument("image value at voxel (" + std::to_string(i) + ", " + std::to_string(j) + ", " +
                                std::to_string(k) + ") inside the region is not finite");
      }
      const double count = double(e - b);
      n += count, w += run_w;
      s = s + Vec3{double((b + e - 1) * (e - b)) / 2, double(j) * count, double(k) * count};
      sw = sw + Vec3{run_wi, double(j) * run_w, double(k) * run_w};
    }
  }
  if (n == 0) return invalid_argument("centre of mass shift of an empty region is undefined");
  if (w == 0) return invalid_argument("image values inside the region sum to 0: no intensity-weighted centroid");
  const Vec3 geometric = g.index_to_physical((1 / n) * s);
  const Vec3 weighted = g.index_to_physical((1 / w) * sw);
  return norm(geometric - weighted);
}

}  // namespace soiq
