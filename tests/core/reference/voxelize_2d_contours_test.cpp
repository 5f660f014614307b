#include "core/reference/voxelize_2d_contours.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/reference/voxelize_3d_raycast.h"
#include "tests/core/reference/reference_test_support.h"

namespace soiq {
namespace {

using test::cube_grid;

// On generic input (no crossing exactly at a centre) the 2D and 3D methods are the same function.
TEST(Voxelize2DContours, AgreesWithTheRaycastOracleOnSpheres) {
  ImageGeometry g = cube_grid(30);
  g.origin_mm = {-7.3, -7.1, -6.9};
  g.spacing_mm = {0.5, 0.5, 0.5};
  for (int rings : {5, 16, 40}) {
    const TriangleMesh m = test::uv_sphere_mesh({0.11, -0.07, 0.13}, 6.3, rings, 2 * rings);
    const auto a = voxelize_2d_contours(m, g);
    const auto b = voxelize_3d_raycast(m, g);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_GT(voxel_count(*a), 1000);
    EXPECT_EQ(a->runs, b->runs) << rings << " rings";
    EXPECT_EQ(a->line_start, b->line_start) << rings << " rings";
  }
}

// Sphere centred on a voxel centre, vertices on grid planes: many vertices on slice planes and
// contour points on rows; still the same voxels as the raycast oracle.
TEST(Voxelize2DContours, AgreesWithTheRaycastOracleWhenVerticesSitOnSlicePlanes) {
  const ImageGeometry g = cube_grid(17);
  const TriangleMesh m = test::uv_sphere_mesh({8, 8, 8}, 6, 4, 8);  // poles and equator on planes
  const auto a = voxelize_2d_contours(m, g);
  const auto b = voxelize_3d_raycast(m, g);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(voxel_count(*a), voxel_count(*b));
  EXPECT_EQ(a->runs, b->runs);
}

}  // namespace
}  // namespace soiq
