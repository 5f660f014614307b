#include "tests/support/simulated_models.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace soiq::bench {

namespace {

constexpr double kStripeThicknessMm = 4;
constexpr int kMarginVoxels = 3;

bool inside(const SimModel& m, double x, double y, double z) {
  const double r = std::sqrt(x * x + y * y + z * z);
  if (r < m.r1_mm) return false;
  if (r <= m.r2_mm) return true;
  const int w = int(m.stripe_r3_mm.size());
  const double rho = std::sqrt(x * x + y * y);
  for (int s = 0; s < w; ++s) {
    const double z_s = -m.r2_mm / 2 + (s + 0.5) * m.r2_mm / w;
    if (rho <= m.stripe_r3_mm[size_t(s)] && std::abs(z - z_s) <= kStripeThicknessMm / 2) return true;
  }
  return false;
}

}  // namespace

std::vector<SimModel> simulated_models() {
  std::mt19937 g(1);
  auto random_r3 = [&g](int w) {
    std::vector<double> r;
    for (int s = 0; s < w; ++s) r.push_back(55 + 20 * (double(g()) / 4294967296.0));
    return r;
  };
  auto fixed = [](int w, double r3) { return std::vector<double>(size_t(w), r3); };
  std::vector<SimModel> m;
  m.push_back({"SM1", 30, 50, {}});
  m.push_back({"SM2", 45, 50, {}});
  m.push_back({"SM3", 30, 50, fixed(1, 55)});
  m.push_back({"SM4", 45, 50, fixed(1, 60)});
  m.push_back({"SM5", 30, 50, fixed(2, 75)});
  m.push_back({"SM6", 45, 50, fixed(3, 55)});
  m.push_back({"SM7", 30, 50, fixed(4, 60)});
  m.push_back({"SM8", 45, 50, fixed(5, 75)});
  m.push_back({"SM9", 30, 50, random_r3(6)});
  m.push_back({"SM10", 45, 50, random_r3(7)});
  m.push_back({"SM11", 30, 50, fixed(7, 75)});
  return m;
}

Mask simulated_volume(const SimModel& model, double spacing_mm) {
  double extent_xy = model.r2_mm;
  for (double r : model.stripe_r3_mm) extent_xy = std::max(extent_xy, r);
  const int64_t half_xy = int64_t(std::ceil(extent_xy / spacing_mm)) + kMarginVoxels;
  const int64_t half_z = int64_t(std::ceil(model.r2_mm / spacing_mm)) + kMarginVoxels;
  Mask m;
  m.geometry.spacing_mm = {spacing_mm, spacing_mm, spacing_mm};
  m.geometry.dims = {2 * half_xy + 1, 2 * half_xy + 1, 2 * half_z + 1};
  m.geometry.origin_mm = {-double(half_xy) * spacing_mm, -double(half_xy) * spacing_mm, -double(half_z) * spacing_mm};
  m.voxels.assign(size_t(m.geometry.voxel_count()), 0);
  size_t n = 0;
  for (int64_t k = 0; k < m.geometry.dims[2]; ++k) {
    for (int64_t j = 0; j < m.geometry.dims[1]; ++j) {
      for (int64_t i = 0; i < m.geometry.dims[0]; ++i) {
        // Centres as (index - half) * spacing, so the lattice is symmetric about the origin.
        m.voxels[n++] = inside(model, double(i - half_xy) * spacing_mm, double(j - half_xy) * spacing_mm,
                               double(k - half_z) * spacing_mm);
      }
    }
  }
  return m;
}

}  // namespace soiq::bench
