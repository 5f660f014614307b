// Regions around and within a structure: shell(r) and core(r) of a sphere against the analytic
// volumes, on isotropic and anisotropic grids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/primitives.h"
#include "core/regions/regions.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

constexpr double kRadius = 20.0;
const Vec3 kCentre{28.3, 27.7, 28.1};  // off the lattice, so no symmetry helps the counts
// The UV sphere (200 rings, 400 segments) is inscribed: its faces lie within
// 20 (1 - cos(pi/400)^2) = 1.2e-3 mm inside the sphere.
constexpr double kInscribedGap = 2e-3;

// A sphere of radius 20 mm (a fine UV sphere through the 1D method) on a grid of `spacing`.
RunLengthVolume sphere_volume(const Vec3& spacing) {
  ImageGeometry g;
  g.spacing_mm = spacing;
  for (int a = 0; a < 3; ++a) g.dims[size_t(a)] = int64_t(std::ceil(57.0 / spacing[size_t(a)]));
  auto v = voxelize_1d(uv_sphere(kCentre, kRadius, 200, 400), g);
  EXPECT_TRUE(v.ok()) << v.status().to_string();
  return v.ok() ? std::move(v)->volume : empty_volume(g);
}

double volume_mm3(const RunLengthVolume& v) { return double(voxel_count(v)) * v.geometry.voxel_volume_mm3(); }

RunLengthVolume must_region(const RunLengthVolume& s, RegionKind kind, double r) {
  auto v = region(s, {kind, r}, {.threads = 2});
  EXPECT_TRUE(v.ok()) << v.status().to_string();
  return v.ok() ? std::move(v).value() : empty_volume(s.geometry);
}

// Signed error of the shell(r) and core(r) volumes against the analytic ones, in mm³.
struct VolumeErrors {
  double shell_mm3, core_mm3;
};
VolumeErrors sphere_region_errors(const Vec3& spacing, double r) {
  const double pi = std::numbers::pi;
  const RunLengthVolume s = sphere_volume(spacing);
  const double shell = 4.0 / 3 * pi * (std::pow(kRadius + r, 3) - std::pow(kRadius, 3));
  const double core = 4.0 / 3 * pi * std::pow(kRadius - r, 3);
  return {volume_mm3(must_region(s, RegionKind::kShell, r)) - shell,
          volume_mm3(must_region(s, RegionKind::kCore, r)) - core};
}

class RegionsSphere : public ::testing::TestWithParam<Vec3> {};

// Exact, voxel by voxel. A shell voxel is outside the (inscribed) sphere and within r of an inside
// centre, so its centre lies in (R - gap, R + r]. An inside voxel deeper than R - r - gap is farther
// than r from every outside centre, so it is in the core. A dilation by voxel steps breaks the first
// on the anisotropic grid: ceil(2 / 0.7) = 3 steps along i reach 2.1 mm, one step along k 2.5 mm.
TEST_P(RegionsSphere, Shell2LiesInTheAnalyticShellAndCore2HoldsEveryDeeperVoxel) {
  const double r = 2.0;
  const RunLengthVolume s = sphere_volume(GetParam());
  auto inside = to_mask(s);
  auto shell = to_mask(must_region(s, RegionKind::kShell, r));
  auto core = to_mask(must_region(s, RegionKind::kCore, r));
  ASSERT_TRUE(inside.ok() && shell.ok() && core.ok());
  const auto& d = s.geometry.dims;
  int64_t shell_count = 0;
  for (int64_t k = 0; k < d[2]; ++k)
    for (int64_t j = 0; j < d[1]; ++j)
      for (int64_t i = 0; i < d[0]; ++i) {
        const size_t n = size_t(i + d[0] * (j + d[1] * k));
        const double rho = norm(s.geometry.index_to_physical({double(i), double(j), double(k)}) - kCentre);
        if (shell->voxels[n]) {
          ++shell_count;
          EXPECT_GT(rho, kRadius - kInscribedGap) << i << "," << j << "," << k;
          EXPECT_LE(rho, kRadius + r + 1e-9) << i << "," << j << "," << k;
        }
        if (core->voxels[n]) {
          EXPECT_EQ(inside->voxels[n], 1) << i << "," << j << "," << k;
        }
        if (inside->voxels[n] && rho < kRadius - r - kInscribedGap) {
          EXPECT_EQ(core->voxels[n], 1) << i << "," << j << "," << k;
        }
      }
  EXPECT_GT(shell_count, 0);
}

// The analytic volumes, within an error derived from the voxel-centre definition. The shell is the
// centres of U minus the inside, U the union of balls of radius r around the inside centres I. By
// the test above it lies within the analytic shell; it misses the centres between the boundary of U
// and the sphere of radius R + r. That boundary is the offset by r of the hull of I, less the scallops
// between neighbouring balls (depth a² / 2r for centres a apart), and the hull lies below the sphere
// by the gap to the outermost lattice plane facing each direction: under one lattice step, half of
// one on average, i.e. half the spacing for a face normal to an axis. So we allow half the largest
// spacing over the outer surface: |error| <= 4 pi (R + r)^2 h_max / 2. The core is the mirror case
// (the outside centres' hull, above the sphere), over the inner surface 4 pi (R - r)^2. The lattice
// count's own error is orders smaller (the inside volume is within 0.05 %).
// Measured (mm³): 1 mm grid shell -1702 of 11092 (tolerance 3041), core +1032 of 24429 (2036);
// 0.7 x 1 x 2.5 mm shell -3917 (7603), core +2582 (5089). The shell errs low on the anisotropic grid
// because no centre lies within 2 mm above a face normal to the 2.5 mm axis: with centres only, a
// shell thinner than a spacing is empty along it.
TEST_P(RegionsSphere, Shell2AndCore2VolumesMatchAnalyticWithinHalfTheLargestSpacingOverTheirSurface) {
  const double pi = std::numbers::pi, r = 2.0;
  const Vec3 h = GetParam();
  const double h_max = std::max({h[0], h[1], h[2]});
  const VolumeErrors e = sphere_region_errors(h, r);
  EXPECT_LE(std::abs(e.shell_mm3), 4 * pi * (kRadius + r) * (kRadius + r) * h_max / 2);
  EXPECT_LE(std::abs(e.core_mm3), 4 * pi * (kRadius - r) * (kRadius - r) * h_max / 2);
  // The shell only misses centres of the analytic shell (test above), never gains any, so its error
  // is a deficit; the lattice count's own noise (tens of mm³) is far below the deficits measured.
  EXPECT_LT(e.shell_mm3, 0);
}

// A discretisation error vanishes with the spacing: halving it must at least shrink the error by a
// third (measured: 0.52 and 0.26 for the shell, 0.55 and 0.25 for the core, 1 mm and anisotropic).
TEST_P(RegionsSphere, Shell2AndCore2ErrorsShrinkWhenTheSpacingIsHalved) {
  const Vec3 h = GetParam();
  const VolumeErrors coarse = sphere_region_errors(h, 2.0);
  const VolumeErrors fine = sphere_region_errors(0.5 * h, 2.0);
  EXPECT_LE(std::abs(fine.shell_mm3), 0.7 * std::abs(coarse.shell_mm3));
  EXPECT_LE(std::abs(fine.core_mm3), 0.7 * std::abs(coarse.core_mm3));
}

INSTANTIATE_TEST_SUITE_P(Grids, RegionsSphere, ::testing::Values(Vec3{1, 1, 1}, Vec3{0.7, 1.0, 2.5}),
                         [](const auto& info) { return info.index == 0 ? "Isotropic1mm" : "Anisotropic07x1x25mm"; });

}  // namespace
}  // namespace soiq
