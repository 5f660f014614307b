#include "core/reference/voxelize_3d_raycast.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/core/reference/reference_test_support.h"

namespace soiq {
namespace {

using test::cube_grid;
using test::differing;
using test::expected_mask;
using test::in;

TEST(Voxelize3DRaycast, HalfIntegerBoxHoldsExactlyTheCentresInside) {
  const ImageGeometry g = cube_grid(8);
  const auto r = voxelize_3d_raycast(test::tessellated_box({-0.5, 0.5, 1.5}, {3.5, 2.5, 5.5}), g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(*r), 4 * 2 * 4);
  EXPECT_EQ(
      differing(*r, expected_mask(g, [](auto i, auto j, auto k) { return in(i, 0, 4) && in(j, 1, 3) && in(k, 2, 6); })),
      0);
}

// Hand count: the line (j, k) is perturbed to (j + e, k + e^2), so it is inside the projection
// [2,4] x [0,3] iff j in {2, 3} and k in {0, 1, 2} (faces y = lo and z = lo in, y = hi and z = hi
// out); along x the centre on the entering face x = 1 is inside, the one on the leaving face x = 5
// is not. Every axis is half-open: 4 x 2 x 3 = 24 voxels, the box's volume.
TEST(Voxelize3DRaycast, IntegerBoxIsHalfOpenOnEveryAxis) {
  const ImageGeometry g = cube_grid(8);
  const auto expected =
      expected_mask(g, [](auto i, auto j, auto k) { return in(i, 1, 5) && in(j, 2, 4) && in(k, 0, 3); });
  const auto r = voxelize_3d_raycast(test::tessellated_box({1, 2, 0}, {5, 4, 3}), g);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(voxel_count(*r), 24);
  EXPECT_EQ(differing(*r, expected), 0);
}

// The same box with unit-square facets: lines now run exactly through shared edges and vertices,
// and each must still be counted once.
TEST(Voxelize3DRaycast, LinesThroughSharedEdgesAndVerticesCountOnce) {
  const ImageGeometry g = cube_grid(8);
  const auto expected =
      expected_mask(g, [](auto i, auto j, auto k) { return in(i, 1, 5) && in(j, 2, 4) && in(k, 0, 3); });
  for (int n : {2, 4, 12}) {
    const auto r = voxelize_3d_raycast(test::tessellated_box({1, 2, 0}, {5, 4, 3}, n), g);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(differing(*r, expected), 0) << n << " facets per edge";
  }
}

// Octahedron |x|+|y|+|z| <= 2 on the lattice (centre at voxel (3,3,3)): 7 centres strictly inside;
// of the 18 on the surface, a centre is kept iff the perturbation (+x first, then +y, then +z)
// points into the solid at every face through it, i.e. every such face has n_x < 0: the 4 with
// x = -1 and the vertex x = -2. Hand count: 12.
TEST(Voxelize3DRaycast, LatticeOctahedronFollowsThePerturbation) {
  const ImageGeometry g = cube_grid(7);
  const auto expected = expected_mask(g, [](int64_t i, int64_t j, int64_t k) {
    const int64_t x = i - 3, y = j - 3, z = k - 3, l1 = std::abs(x) + std::abs(y) + std::abs(z);
    return l1 < 2 || (l1 == 2 && x < 0);
  });
  const auto r = voxelize_3d_raycast(test::octahedron({3, 3, 3}, 2), g);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(voxel_count(*r), 12);
  EXPECT_EQ(differing(*r, expected), 0);
}

TEST(Voxelize3DRaycast, SphereMatchesAnalyticTestAwayFromTheSurface) {
  ImageGeometry g = cube_grid(24);
  g.origin_mm = {-6.1, -5.7, -6.3};
  g.spacing_mm = {0.55, 0.5, 0.6};
  const Vec3 c{0.3, -0.2, 0.4};
  const double r = 5.2;
  const TriangleMesh m = test::uv_sphere_mesh(c, r, 48, 96);
  const double s = test::sagitta(m, c, r);
  ASSERT_LT(s, 0.02);
  const auto v = voxelize_3d_raycast(m, g);
  ASSERT_TRUE(v.ok());
  const auto mask = to_mask(*v);
  int64_t checked = 0, wrong = 0;
  for (int64_t k = 0; k < 24; ++k)
    for (int64_t j = 0; j < 24; ++j)
      for (int64_t i = 0; i < 24; ++i) {
        const double d = norm(g.index_to_physical({double(i), double(j), double(k)}) - c);
        // Centres within the sagitta band (plus 1e-9 for rounding) may go either way.
        if (d > r - s - 1e-9 && d < r + 1e-9) continue;
        ++checked;
        wrong += mask->voxels[size_t(i + 24 * (j + 24 * k))] != (d < r);
      }
  EXPECT_GT(checked, 13000);
  EXPECT_EQ(wrong, 0);
}

// Two boxes overlapping in [2,4) x [2,4) x [2,4): the overlap has winding number 2.
TEST(Voxelize3DRaycast, NonZeroKeepsTheOverlapOfTwoBoxes) {
  const ImageGeometry g = cube_grid(8);
  const TriangleMesh m =
      test::merged(test::tessellated_box({0, 0, 0}, {4, 4, 4}), test::tessellated_box({2, 2, 2}, {6, 6, 6}));
  auto box_a = [](auto i, auto j, auto k) { return in(i, 0, 4) && in(j, 0, 4) && in(k, 0, 4); };
  auto box_b = [](auto i, auto j, auto k) { return in(i, 2, 6) && in(j, 2, 6) && in(k, 2, 6); };

  const auto nonzero = voxelize_3d_raycast(m, g, FillRule::kNonZero);
  ASSERT_TRUE(nonzero.ok());
  EXPECT_EQ(voxel_count(*nonzero), 64 + 64 - 8);
  EXPECT_EQ(
      differing(*nonzero, expected_mask(g, [&](auto i, auto j, auto k) { return box_a(i, j, k) || box_b(i, j, k); })),
      0);

  const auto even_odd = voxelize_3d_raycast(m, g, FillRule::kEvenOdd);
  ASSERT_TRUE(even_odd.ok());
  EXPECT_EQ(voxel_count(*even_odd), 64 + 64 - 2 * 8);
  EXPECT_EQ(
      differing(*even_odd, expected_mask(g, [&](auto i, auto j, auto k) { return box_a(i, j, k) != box_b(i, j, k); })),
      0);
}

// A random mask's voxel-face surface comes back as the mask, on a rotated, anisotropic grid.
TEST(Voxelize3DRaycast, VoxelFaceSurfaceOfAMaskGivesTheMaskBack) {
  Mask mask;
  mask.geometry.dims = {9, 8, 7};
  mask.geometry.spacing_mm = {0.7, 1.1, 2.5};
  mask.geometry.origin_mm = {10, -20, 30};
  mask.geometry.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};  // a rotation about z
  std::mt19937 rng(7);
  mask.voxels.resize(size_t(mask.geometry.voxel_count()));
  for (auto& v : mask.voxels) v = (rng() % 3) == 0;
  const auto r = voxelize_3d_raycast(test::cuberille(mask), mask.geometry);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(differing(*r, mask.voxels), 0);
}

TEST(Voxelize3DRaycast, InwardFacingSurfaceGivesTheSameVoxels) {
  const ImageGeometry g = cube_grid(8);
  TriangleMesh m = test::octahedron({3.2, 3.6, 2.9}, 2.7);
  const auto outward = voxelize_3d_raycast(m, g);
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  const auto inward = voxelize_3d_raycast(m, g);
  ASSERT_TRUE(outward.ok() && inward.ok());
  EXPECT_GT(voxel_count(*outward), 0);
  EXPECT_EQ(outward->runs, inward->runs);
  EXPECT_EQ(outward->line_start, inward->line_start);
}

TEST(Voxelize3DRaycast, EmptyMeshIsInvalidArgument) {
  const auto r = voxelize_3d_raycast(TriangleMesh{}, cube_grid(4));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("no triangles"), std::string::npos);
}

TEST(Voxelize3DRaycast, VertexIndexOutOfRangeIsInvalidArgument) {
  TriangleMesh m = test::octahedron({3, 3, 3}, 2);
  m.triangles[2][1] = 99;
  const auto r = voxelize_3d_raycast(m, cube_grid(4));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("vertex 99"), std::string::npos);
}

TEST(Voxelize3DRaycast, BadSpacingIsInvalidArgument) {
  ImageGeometry g = cube_grid(4);
  g.spacing_mm[1] = 0;
  const auto r = voxelize_3d_raycast(test::octahedron({3, 3, 3}, 2), g);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("spacing"), std::string::npos);
}

}  // namespace
}  // namespace soiq
