#include "core/reference/voxelize_2d_contours.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/reference/voxelize_3d_raycast.h"
#include "tests/core/reference/reference_test_support.h"

namespace soiq {
namespace {

using test::cube_grid;
using test::differing;
using test::expected_mask;
using test::in;

TEST(Voxelize2DContours, HalfIntegerBoxHoldsExactlyTheCentresInside) {
  const ImageGeometry g = cube_grid(8);
  const auto r = voxelize_2d_contours(test::tessellated_box({-0.5, 0.5, 1.5}, {3.5, 2.5, 5.5}), g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(*r), 4 * 2 * 4);
  EXPECT_EQ(
      differing(*r, expected_mask(g, [](auto i, auto j, auto k) { return in(i, 0, 4) && in(j, 1, 3) && in(k, 2, 6); })),
      0);
}

// Hand count as in Voxelize3DRaycast: vertices on the plane z = k count as below it (z = k + e^2)
// and contour points on the row y = j as below it (y = j + e), so the faces z = lo, y = lo and the
// entering face x = lo are in, z = hi, y = hi and the leaving face x = hi out: 4 x 2 x 3 voxels.
TEST(Voxelize2DContours, IntegerBoxIsHalfOpenOnEveryAxis) {
  const ImageGeometry g = cube_grid(8);
  const auto expected =
      expected_mask(g, [](auto i, auto j, auto k) { return in(i, 1, 5) && in(j, 2, 4) && in(k, 0, 3); });
  for (int n : {1, 2, 4, 12}) {
    const auto r = voxelize_2d_contours(test::tessellated_box({1, 2, 0}, {5, 4, 3}, n), g);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(voxel_count(*r), 24) << n << " facets per edge";
    EXPECT_EQ(differing(*r, expected), 0) << n << " facets per edge";
  }
}

// Slices through vertices and rows through contour vertices: the hand count of Voxelize3DRaycast.
TEST(Voxelize2DContours, LatticeOctahedronFollowsThePerturbation) {
  const ImageGeometry g = cube_grid(7);
  const auto expected = expected_mask(g, [](int64_t i, int64_t j, int64_t k) {
    const int64_t x = i - 3, y = j - 3, z = k - 3, l1 = std::abs(x) + std::abs(y) + std::abs(z);
    return l1 < 2 || (l1 == 2 && x < 0);
  });
  const auto r = voxelize_2d_contours(test::octahedron({3, 3, 3}, 2), g);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(voxel_count(*r), 12);
  EXPECT_EQ(differing(*r, expected), 0);
}

TEST(Voxelize2DContours, NonZeroKeepsTheOverlapAndEvenOddDropsIt) {
  const ImageGeometry g = cube_grid(8);
  const TriangleMesh m =
      test::merged(test::tessellated_box({0, 0, 0}, {4, 4, 4}), test::tessellated_box({2, 2, 2}, {6, 6, 6}));
  auto box_a = [](auto i, auto j, auto k) { return in(i, 0, 4) && in(j, 0, 4) && in(k, 0, 4); };
  auto box_b = [](auto i, auto j, auto k) { return in(i, 2, 6) && in(j, 2, 6) && in(k, 2, 6); };
  const auto nonzero = voxelize_2d_contours(m, g, FillRule::kNonZero);
  const auto even_odd = voxelize_2d_contours(m, g, FillRule::kEvenOdd);
  ASSERT_TRUE(nonzero.ok() && even_odd.ok());
  EXPECT_EQ(
      differing(*nonzero, expected_mask(g, [&](auto i, auto j, auto k) { return box_a(i, j, k) || box_b(i, j, k); })),
      0);
  EXPECT_EQ(
      differing(*even_odd, expected_mask(g, [&](auto i, auto j, auto k) { return box_a(i, j, k) != box_b(i, j, k); })),
      0);
}

TEST(Voxelize2DContours, VoxelFaceSurfaceOfAMaskGivesTheMaskBack) {
  Mask mask;
  mask.geometry.dims = {9, 8, 7};
  mask.geometry.spacing_mm = {0.7, 1.1, 2.5};
  mask.geometry.origin_mm = {10, -20, 30};
  mask.geometry.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  std::mt19937 rng(11);
  mask.voxels.resize(size_t(mask.geometry.voxel_count()));
  for (auto& v : mask.voxels) v = (rng() % 3) == 0;
  const auto r = voxelize_2d_contours(test::cuberille(mask), mask.geometry);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(differing(*r, mask.voxels), 0);
}

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

TEST(Voxelize2DContours, EmptyMeshIsInvalidArgument) {
  const auto r = voxelize_2d_contours(TriangleMesh{}, cube_grid(4));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
