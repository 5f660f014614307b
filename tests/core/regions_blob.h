#pragma once
// The structure of the region tests (tests/core/regions_*_test.cpp): random overlapping balls on an
// anisotropic grid.

#include <cstdint>
#include <random>
#include <vector>

#include "core/base/image.h"
#include "core/base/image_geometry.h"
#include "core/base/vec3.h"

namespace soiq::testing {

// A blob of random overlapping balls that touches the grid border, on a 0.7 x 1.0 x 2.5 mm grid.
inline Mask random_blob(uint64_t seed) {
  Mask m;
  m.geometry.dims = {26, 18, 9};
  m.geometry.spacing_mm = {0.7, 1.0, 2.5};
  m.voxels.assign(26 * 18 * 9, 0);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(0, 17.5), y(0, 17), z(0, 20), rad(1.5, 5);
  for (int b = 0; b < 6; ++b) {
    const Vec3 c{x(rng), y(rng), z(rng)};
    const double r = rad(rng);
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 18; ++j)
        for (int i = 0; i < 26; ++i) {
          if (norm(m.geometry.index_to_physical({double(i), double(j), double(k)}) - c) <= r) {
            m.voxels[size_t(i + 26 * (j + 18 * k))] = 1;
          }
        }
  }
  return m;
}

}  // namespace soiq::testing
