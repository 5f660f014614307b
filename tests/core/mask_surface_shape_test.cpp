// The mask-surface features from runs (mask_surface_sweep, mask_surface_shape,
// mask_maximum_2d_diameters) against the same features of the marching-cubes mesh they stand for,
// on random masks (anisotropic, oblique, touching the grid border, many ambiguous cubes), and
// against PyRadiomics' published brain1 values (REFERENCE_VALUES.md).
#include "core/features/mask_surface_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/features/marching_cubes_table.h"
#include "core/features/mask_maximum_2d_diameters.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/io/marching_cubes.h"
#include "core/io/read_image.h"

namespace soiq {
namespace {

// Both paths sum the same real numbers in another order (and map vertices to mm by another
// rounding): relative agreement to 1e-12 is rounding.
constexpr double kRounding = 1e-12;

void expect_same(double from_runs, double from_mesh, const char* what, int trial) {
  EXPECT_NEAR(from_runs, from_mesh, kRounding * std::fabs(from_mesh)) << what << ", trial " << trial;
}

void expect_matches_marching_cubes(const Mask& mask, int trial) {
  const auto mesh = marching_cubes(mask);
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  const auto want = surface_shape(*mesh, mask.geometry.direction);
  ASSERT_TRUE(want.ok()) << want.status().to_string();
  const auto want_2d = maximum_2d_diameters(*mesh, mask.geometry);
  ASSERT_TRUE(want_2d.ok());
  const auto sweep = mask_surface_sweep(from_mask(mask));
  ASSERT_TRUE(sweep.ok()) << sweep.status().to_string();
  const auto got = mask_surface_shape(*sweep, mask.geometry, marching_cubes_table());
  ASSERT_TRUE(got.ok()) << got.status().to_string();
  const auto got_2d = mask_maximum_2d_diameters(*sweep, mask.geometry);
  ASSERT_TRUE(got_2d.ok());
  expect_same(got->mesh_volume_mm3, want->mesh_volume_mm3, "mesh volume", trial);
  expect_same(got->surface_area_mm2, want->surface_area_mm2, "area", trial);
  expect_same(got->sphericity, want->sphericity, "sphericity", trial);
  expect_same(got->maximum_3d_diameter_mm, want->maximum_3d_diameter_mm, "3D diameter", trial);
  expect_same(got->convex_hull_volume_mm3, want->convex_hull_volume_mm3, "hull volume", trial);
  expect_same(got->convex_hull_area_mm2, want->convex_hull_area_mm2, "hull area", trial);
  expect_same(got->volume_density_aabb, want->volume_density_aabb, "volume density aabb", trial);
  expect_same(got->area_density_aabb, want->area_density_aabb, "area density aabb", trial);
  expect_same(got_2d->slice_mm, want_2d->slice_mm, "2D slice", trial);
  expect_same(got_2d->column_mm, want_2d->column_mm, "2D column", trial);
  expect_same(got_2d->row_mm, want_2d->row_mm, "2D row", trial);
}

TEST(MaskSurfaceShape, EqualsMarchingCubesMeshOnRandomMasks) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 60; ++trial) {
    Mask m;
    std::uniform_int_distribution<int64_t> dim(1, 9);
    m.geometry.dims = {dim(rng), dim(rng), dim(rng)};
    m.geometry.spacing_mm = trial % 2 ? Vec3{0.7, 1.3, 2.5} : Vec3{1, 1, 1};
    m.geometry.origin_mm = {-3.25, 17.5, 4};
    if (trial % 3 == 0) {
      const double c = std::cos(0.4), s = std::sin(0.4);
      m.geometry.direction = {{{c, 0, -s}, {0, -1, 0}, {s, 0, c}}};  // rotation times a mirror
    }
    // Sparse to dense: isolated voxels, diagonal contacts (ambiguous cubes) and solid parts.
    const double fill = 0.15 + 0.7 * double(trial % 5) / 4;
    std::bernoulli_distribution inside(fill);
    m.voxels.resize(size_t(m.geometry.voxel_count()));
    bool any = false;
    for (auto& v : m.voxels) any |= (v = inside(rng) ? 1 : 0) != 0;
    if (!any) m.voxels[0] = 1;
    // A flat or collinear set has no 3D hull; marching_cubes' vertices never are (one voxel
    // already gives an octahedron).
    expect_matches_marching_cubes(m, trial);
  }
}

TEST(MaskSurfaceShape, EqualsMarchingCubesMeshOnABall) {
  Mask m;
  m.geometry.dims = {23, 21, 19};
  m.geometry.spacing_mm = {0.8, 0.8, 1.5};
  m.voxels.resize(size_t(m.geometry.voxel_count()));
  size_t n = 0;
  for (int k = 0; k < 19; ++k)
    for (int j = 0; j < 21; ++j)
      for (int i = 0; i < 23; ++i) {
        const double x = (i - 11) * 0.8, y = (j - 10) * 0.8, z = (k - 9) * 1.5;
        m.voxels[n++] = x * x + y * y + z * z <= 64 ? 1 : 0;
      }
  expect_matches_marching_cubes(m, -1);
}

TEST(MaskSurfaceShape, PyRadiomicsBrain1FromRuns) {
  const auto label = read_image(std::string(SOIQ_TEST_DATA_DIR) + "/pyradiomics/brain1_label.nrrd");
  ASSERT_TRUE(label.ok()) << label.status().to_string();
  const Mask mask = mask_from_image(*label, 1);
  expect_matches_marching_cubes(mask, -2);
  const auto sweep = mask_surface_sweep(from_mask(mask));
  ASSERT_TRUE(sweep.ok());
  const auto s = mask_surface_shape(*sweep, mask.geometry, marching_cubes_table());
  const auto d = mask_maximum_2d_diameters(*sweep, mask.geometry);
  ASSERT_TRUE(s.ok() && d.ok());
  // REFERENCE_VALUES.md: vertex-position features to 1e-9 relative.
  EXPECT_NEAR(s->maximum_3d_diameter_mm, 69.6009903059, 1e-9 * 69.6009903059);
  EXPECT_NEAR(d->slice_mm, 53.5939777692, 1e-9 * 53.5939777692);
  EXPECT_NEAR(d->column_mm, 49.4908549791, 1e-9 * 49.4908549791);
  EXPECT_NEAR(d->row_mm, 65.8890595172, 1e-9 * 65.8890595172);
  // VTK's table: within 0.5 % of PyRadiomics' mesh volume and area.
  EXPECT_NEAR(s->mesh_volume_mm3, 16149.4954427, 0.005 * 16149.4954427);
  EXPECT_NEAR(s->surface_area_mm2, 6433.7343171, 0.005 * 6433.7343171);
}

TEST(MaskSurfaceShape, EmptyMaskIsInvalidArgument) {
  ImageGeometry g;
  g.dims = {3, 3, 3};
  const auto sweep = mask_surface_sweep(empty_volume(g));
  ASSERT_TRUE(sweep.ok());
  EXPECT_TRUE(sweep->empty);
  const auto s = mask_surface_shape(*sweep, g, marching_cubes_table());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.status().message().find("empty mask"), std::string::npos);
}

}  // namespace
}  // namespace soiq
