// Hand counts that both reference methods (the paper's 2D and 3D methods, core/reference/) must
// reproduce exactly: one parameterised suite, so a case is written once and proves both oracles.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <random>
#include <string>

#include "core/reference/voxelize_2d_contours.h"
#include "core/reference/voxelize_3d_raycast.h"
#include "tests/core/reference/reference_test_support.h"

namespace soiq {
namespace {

using test::cube_grid;
using test::differing;
using test::expected_mask;
using test::in;

struct ReferenceMethod {
  std::string name;
  Result<RunLengthVolume> (*voxelize)(const TriangleMesh&, const ImageGeometry&, FillRule);
  unsigned mask_seed;  // the random mask of VoxelFaceSurfaceOfAMaskGivesTheMaskBack
};

void PrintTo(const ReferenceMethod& m, std::ostream* os) { *os << m.name; }

class ReferenceMethods : public ::testing::TestWithParam<ReferenceMethod> {
 protected:
  Result<RunLengthVolume> run(const TriangleMesh& m, const ImageGeometry& g, FillRule rule = FillRule::kNonZero) {
    return GetParam().voxelize(m, g, rule);
  }
};

TEST_P(ReferenceMethods, HalfIntegerBoxHoldsExactlyTheCentresInside) {
  const ImageGeometry g = cube_grid(8);
  const auto r = run(test::tessellated_box({-0.5, 0.5, 1.5}, {3.5, 2.5, 5.5}), g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(*r), 4 * 2 * 4);
  EXPECT_EQ(
      differing(*r, expected_mask(g, [](auto i, auto j, auto k) { return in(i, 0, 4) && in(j, 1, 3) && in(k, 2, 6); })),
      0);
}

// Hand count: the line (j, k) is perturbed to (j + e, k + e^2) (in 2D: vertices on the plane z = k
// count as below it, contour points on the row y = j as below it), so it is inside the projection
// [2,4] x [0,3] iff j in {2, 3} and k in {0, 1, 2}; along x the centre on the entering face x = 1 is
// inside, the one on the leaving face x = 5 is not. Every axis is half-open: 4 x 2 x 3 = 24 voxels.
// With n x n facets per face, lines also run exactly through shared edges and vertices, and each
// must still be counted once.
TEST_P(ReferenceMethods, IntegerBoxIsHalfOpenOnEveryAxis) {
  const ImageGeometry g = cube_grid(8);
  const auto expected =
      expected_mask(g, [](auto i, auto j, auto k) { return in(i, 1, 5) && in(j, 2, 4) && in(k, 0, 3); });
  for (int n : {1, 2, 4, 12}) {
    const auto r = run(test::tessellated_box({1, 2, 0}, {5, 4, 3}, n), g);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(voxel_count(*r), 24) << n << " facets per edge";
    EXPECT_EQ(differing(*r, expected), 0) << n << " facets per edge";
  }
}

// Octahedron |x|+|y|+|z| <= 2 on the lattice (centre at voxel (3,3,3)): 7 centres strictly inside;
// of the 18 on the surface, a centre is kept iff the perturbation (+x first, then +y, then +z)
// points into the solid at every face through it, i.e. every such face has n_x < 0: the 4 with
// x = -1 and the vertex x = -2. Hand count: 12.
TEST_P(ReferenceMethods, LatticeOctahedronFollowsThePerturbation) {
  const ImageGeometry g = cube_grid(7);
  const auto expected = expected_mask(g, [](int64_t i, int64_t j, int64_t k) {
    const int64_t x = i - 3, y = j - 3, z = k - 3, l1 = std::abs(x) + std::abs(y) + std::abs(z);
    return l1 < 2 || (l1 == 2 && x < 0);
  });
  const auto r = run(test::octahedron({3, 3, 3}, 2), g);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(voxel_count(*r), 12);
  EXPECT_EQ(differing(*r, expected), 0);
}

// Two boxes overlapping in [2,4) x [2,4) x [2,4): the overlap has winding number 2.
TEST_P(ReferenceMethods, NonZeroKeepsTheOverlapAndEvenOddDropsIt) {
  const ImageGeometry g = cube_grid(8);
  const TriangleMesh m =
      test::merged(test::tessellated_box({0, 0, 0}, {4, 4, 4}), test::tessellated_box({2, 2, 2}, {6, 6, 6}));
  auto box_a = [](auto i, auto j, auto k) { return in(i, 0, 4) && in(j, 0, 4) && in(k, 0, 4); };
  auto box_b = [](auto i, auto j, auto k) { return in(i, 2, 6) && in(j, 2, 6) && in(k, 2, 6); };

  const auto nonzero = run(m, g, FillRule::kNonZero);
  ASSERT_TRUE(nonzero.ok());
  EXPECT_EQ(voxel_count(*nonzero), 64 + 64 - 8);
  EXPECT_EQ(
      differing(*nonzero, expected_mask(g, [&](auto i, auto j, auto k) { return box_a(i, j, k) || box_b(i, j, k); })),
      0);

  const auto even_odd = run(m, g, FillRule::kEvenOdd);
  ASSERT_TRUE(even_odd.ok());
  EXPECT_EQ(voxel_count(*even_odd), 64 + 64 - 2 * 8);
  EXPECT_EQ(
      differing(*even_odd, expected_mask(g, [&](auto i, auto j, auto k) { return box_a(i, j, k) != box_b(i, j, k); })),
      0);
}

// A random mask's voxel-face surface comes back as the mask, on a rotated, anisotropic grid.
TEST_P(ReferenceMethods, VoxelFaceSurfaceOfAMaskGivesTheMaskBack) {
  Mask mask;
  mask.geometry.dims = {9, 8, 7};
  mask.geometry.spacing_mm = {0.7, 1.1, 2.5};
  mask.geometry.origin_mm = {10, -20, 30};
  mask.geometry.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};  // a rotation about z
  std::mt19937 rng(GetParam().mask_seed);
  mask.voxels.resize(size_t(mask.geometry.voxel_count()));
  for (auto& v : mask.voxels) v = (rng() % 3) == 0;
  const auto r = run(test::cuberille(mask), mask.geometry);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(differing(*r, mask.voxels), 0);
}

TEST_P(ReferenceMethods, EmptyMeshIsInvalidArgument) {
  const auto r = run(TriangleMesh{}, cube_grid(4));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("no triangles"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Oracles, ReferenceMethods,
                         ::testing::Values(ReferenceMethod{"Voxelize2DContours", voxelize_2d_contours, 11},
                                           ReferenceMethod{"Voxelize3DRaycast", voxelize_3d_raycast, 7}),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace soiq
