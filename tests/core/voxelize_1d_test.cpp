// The 1D method against hand counts, analytic shapes and its own invariants. Exact comparison with
// the independent 3D oracle lives in voxelize_1d_oracle_test.cpp.
#include "core/voxelize/voxelize_1d.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/primitives.h"

namespace soiq {
namespace {

ImageGeometry cube_grid(int64_t n, double spacing = 1.0, Vec3 origin = {0, 0, 0}) {
  ImageGeometry g;
  g.dims = {n, n, n};
  g.spacing_mm = {spacing, spacing, spacing};
  g.origin_mm = origin;
  return g;
}

Voxelization must_voxelize(const TriangleMesh& m, const ImageGeometry& g, VoxelizeOptions o = {}) {
  auto r = voxelize_1d(m, g, o);
  EXPECT_TRUE(r.ok()) << r.status().to_string();
  return r.ok() ? std::move(r).value() : Voxelization{};
}

TEST(Voxelize1D, BoxWithHalfIntegerCornersHasExactCount) {
  // Centres 2..7 in x (6), 1..3 in y (3), 4..8 in z (5).
  const auto v = must_voxelize(box({1.5, 0.5, 3.5}, {7.5, 3.5, 8.5}), cube_grid(12));
  EXPECT_EQ(voxel_count(v.volume), 6 * 3 * 5);
}

TEST(Voxelize1D, CentresOnEnteringFaceAreInsideOnLeavingFaceAreNot) {
  // Box [2,6]^3 with faces through voxel centres: along x the runs are half-open [2,6). Along y
  // and z the line is perturbed to (j + e, k + e^2), so y = 2 and z = 2 count, 6 does not.
  const auto v = must_voxelize(box({2, 2, 2}, {6, 6, 6}), cube_grid(9));
  EXPECT_EQ(voxel_count(v.volume), 4 * 4 * 4);
  auto mask = to_mask(v.volume);
  ASSERT_TRUE(mask.ok());
  auto at = [&](int i, int j, int k) { return mask->voxels[size_t(i + 9 * (j + 9 * k))]; };
  EXPECT_EQ(at(2, 2, 2), 1);
  EXPECT_EQ(at(5, 5, 5), 1);
  EXPECT_EQ(at(6, 3, 3), 0);
  EXPECT_EQ(at(3, 6, 3), 0);
  EXPECT_EQ(at(3, 3, 6), 0);
}

TEST(Voxelize1D, GridThatMissesTheMeshIsEmpty) {
  const auto v = must_voxelize(box({100, 100, 100}, {110, 110, 110}), cube_grid(10));
  EXPECT_EQ(voxel_count(v.volume), 0);
}

TEST(Voxelize1D, GridThatCutsTheMeshKeepsTheInsidePart) {
  // Box x in [-5.5, 3.5]: centres 0..3 inside the grid (the rest is cut off).
  const auto v = must_voxelize(box({-5.5, 1.5, 1.5}, {3.5, 4.5, 4.5}), cube_grid(8));
  EXPECT_EQ(voxel_count(v.volume), 4 * 3 * 3);
}

TEST(Voxelize1D, SphereMatchesAnalyticCentresAwayFromTheSurface) {
  const double r = 10.0;
  const Vec3 c{16.2, 15.7, 16.4};
  const TriangleMesh m = uv_sphere(c, r, 200, 400);
  const auto g = cube_grid(33);
  const auto v = must_voxelize(m, g);
  auto mask = to_mask(v.volume);
  ASSERT_TRUE(mask.ok());
  // The inscribed polyhedron lies within 1 - cos(pi/200) * r of the sphere (~1.2e-3 mm):
  // decide only centres farther than 0.01 mm from the sphere.
  int64_t checked = 0;
  for (int k = 0; k < 33; ++k)
    for (int j = 0; j < 33; ++j)
      for (int i = 0; i < 33; ++i) {
        const double d = norm(Vec3{double(i), double(j), double(k)} - c);
        if (std::abs(d - r) < 0.01) continue;
        ++checked;
        EXPECT_EQ(mask->voxels[size_t(i + 33 * (j + 33 * k))], d < r ? 1 : 0) << i << "," << j << "," << k;
      }
  EXPECT_GT(checked, 30000);
}

TEST(Voxelize1D, ThreadCountChangesNothing) {
  const TriangleMesh m = merge(torus({20, 21, 19.5}, 12, 4, 90, 40), uv_sphere({20.3, 20, 20}, 6, 40, 80));
  const auto g = cube_grid(41);
  const auto one = must_voxelize(m, g);
  for (int t : {2, 3, 8}) {
    VoxelizeOptions o;
    o.threads = t;
    const auto many = must_voxelize(m, g, o);
    EXPECT_EQ(one.volume.line_start, many.volume.line_start) << t << " threads";
    EXPECT_EQ(one.volume.runs, many.volume.runs) << t << " threads";
  }
}

// Threads share the triangles, then the slabs of slices: grids with fewer slices than threads, and
// robust mode's open lines (dropped per slab), must come out as with one thread.
TEST(Voxelize1D, ThreadCountChangesNothingOnThinGridsOrOpenSurfaces) {
  const TriangleMesh m = merge(torus({20, 21, 19.5}, 12, 4, 90, 40), uv_sphere({20.3, 20, 20}, 6, 40, 80));
  for (int64_t slices : {1, 2, 3}) {
    ImageGeometry g = cube_grid(41);
    g.dims[2] = slices;
    g.origin_mm[2] = 18.5;
    const auto one = must_voxelize(m, g);
    EXPECT_GT(voxel_count(one.volume), 0) << slices << " slices";
    for (int t : {2, 8}) {
      VoxelizeOptions o;
      o.threads = t;
      EXPECT_EQ(one.volume.runs, must_voxelize(m, g, o).volume.runs) << slices << " slices, " << t << " threads";
    }
  }
  TriangleMesh open = m;
  open.triangles.erase(open.triangles.begin() + 300, open.triangles.begin() + 320);
  VoxelizeOptions robust;
  robust.robust = true;
  const auto one = must_voxelize(open, cube_grid(41), robust);
  robust.threads = 3;
  const auto three = must_voxelize(open, cube_grid(41), robust);
  EXPECT_EQ(one.volume.runs, three.volume.runs);
  EXPECT_EQ(one.volume.line_start, three.volume.line_start);
}

TEST(Voxelize1D, RobustModeEqualsPlainModeOnClosedMeshes) {
  const TriangleMesh m = merge(torus({20, 21, 19.5}, 12, 4, 60, 30), uv_sphere({20.3, 20, 20}, 6, 30, 60));
  const auto g = cube_grid(41);
  VoxelizeOptions robust;
  robust.robust = true;
  EXPECT_EQ(must_voxelize(m, g).volume.runs, must_voxelize(m, g, robust).volume.runs);
}

TEST(Voxelize1D, OverlappingComponentsUnionUnderNonZeroAndXorUnderEvenOdd) {
  const TriangleMesh a = box({1.5, 1.5, 1.5}, {6.5, 6.5, 6.5});  // 5^3 = 125 centres
  const TriangleMesh b = box({4.5, 4.5, 4.5}, {9.5, 9.5, 9.5});  // 125, overlap 2^3 = 8
  const auto g = cube_grid(12);
  EXPECT_EQ(voxel_count(must_voxelize(merge(a, b), g).volume), 125 + 125 - 8);
  VoxelizeOptions eo;
  eo.fill_rule = FillRule::kEvenOdd;
  EXPECT_EQ(voxel_count(must_voxelize(merge(a, b), g, eo).volume), 125 + 125 - 2 * 8);
}

TEST(Voxelize1D, HollowShellLeavesTheCavityEmpty) {
  const TriangleMesh shell =
      merge(box({0.5, 0.5, 0.5}, {9.5, 9.5, 9.5}), flipped(box({2.5, 2.5, 2.5}, {7.5, 7.5, 7.5})));
  EXPECT_EQ(voxel_count(must_voxelize(shell, cube_grid(11)).volume), 9 * 9 * 9 - 5 * 5 * 5);
}

TEST(Voxelize1D, InvertedOrientationGivesTheSameVoxels) {
  const TriangleMesh m = uv_sphere({8.1, 8.2, 7.9}, 5, 20, 40);
  const auto g = cube_grid(17);
  EXPECT_EQ(must_voxelize(m, g).volume.runs, must_voxelize(flipped(m), g).volume.runs);
}

TEST(Voxelize1D, OpenMeshInPlainModeIsRefusedNamingRobustMode) {
  TriangleMesh m = box({1, 1, 1}, {5, 5, 5});
  m.triangles.pop_back();
  auto r = voxelize_1d(m, cube_grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(r.status().message().find("boundary edges"), std::string::npos);
  EXPECT_NE(r.status().message().find("--robust"), std::string::npos);
}

TEST(Voxelize1D, OpenMeshInRobustModeRecoversTheVolume) {
  // A sphere with a small hole (one triangle removed): the 2-of-3 vote still finds the inside.
  const TriangleMesh closed = uv_sphere({10.3, 10.1, 9.8}, 7, 30, 60);
  TriangleMesh open = closed;
  open.triangles.erase(open.triangles.begin() + 700);
  const auto g = cube_grid(21);
  VoxelizeOptions robust;
  robust.robust = true;
  const auto v_open = must_voxelize(open, g, robust);
  const auto v_closed = must_voxelize(closed, g);
  auto cmp = compare(v_open.volume, v_closed.volume);
  ASSERT_TRUE(cmp.ok());
  EXPECT_EQ(cmp->only_a + cmp->only_b, 0);
  EXPECT_EQ(v_open.defects.boundary_edges, 3);
}

TEST(Voxelize1D, HugeGridIsRefusedBeforeAllocating) {
  ImageGeometry g = cube_grid(10000);  // 1e12 voxels
  auto r = voxelize_1d(box({1, 1, 1}, {5, 5, 5}), g);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(r.status().message().find("1e+12 voxels"), std::string::npos) << r.status().message();
}

TEST(Voxelize1D, NanVertexIsInvalidArgument) {
  TriangleMesh m = box({1, 1, 1}, {5, 5, 5});
  m.vertices_mm[3][1] = std::nan("");
  auto r = voxelize_1d(m, cube_grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("NaN"), std::string::npos);
}

TEST(Voxelize1D, IndexOutOfRangeIsInvalidArgument) {
  TriangleMesh m = box({1, 1, 1}, {5, 5, 5});
  m.triangles[0][2] = 99;
  auto r = voxelize_1d(m, cube_grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("out of range"), std::string::npos);
}

TEST(Voxelize1D, BadGeometryIsInvalidArgument) {
  ImageGeometry g = cube_grid(8);
  g.spacing_mm[1] = 0;
  auto r = voxelize_1d(box({1, 1, 1}, {5, 5, 5}), g);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("spacing"), std::string::npos);
}

}  // namespace
}  // namespace soiq
