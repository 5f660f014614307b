#include "client/cohort/blob_image.h"

#include <cmath>

namespace soiq::cohort {

Image blob_image(const ImageStyle& style, const std::vector<PlacedStructure>& structures, double phase) {
  Image image;
  ImageGeometry& g = image.geometry;
  g.dims = style.dims;
  g.spacing_mm = {2, 2, 2};
  for (int a = 0; a < 3; ++a) g.origin_mm[a] = -double(g.dims[a] - 1);  // centred on the origin
  image.voxels.resize(size_t(g.voxel_count()));
  size_t index = 0;
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    for (int64_t j = 0; j < g.dims[1]; ++j) {
      for (int64_t i = 0; i < g.dims[0]; ++i) {
        const Vec3 x = g.index_to_physical({double(i), double(j), double(k)});
        double value = style.background + style.ripple * std::sin(x[0] / 19 + phase) * std::cos(x[1] / 27) + 0.3 * x[2];
        for (const PlacedStructure& s : structures) {
          double d2 = 0;
          for (int a = 0; a < 3; ++a) {
            const double t = (x[a] - s.ellipsoid.centre_mm[a]) / s.ellipsoid.semi_axes_mm[a];
            d2 += t * t;
          }
          value += s.brightness / (1 + std::exp((std::sqrt(d2) - 1.15) * 7));
        }
        image.voxels[index++] = float(value);
      }
    }
  }
  return image;
}

// A stream of its own: the seed xor a constant, so it is not the structures' stream.
double image_phase(uint64_t seed) { return SplitMix64(seed ^ 0x5eedULL).uniform(0, 6.28); }

}  // namespace soiq::cohort
