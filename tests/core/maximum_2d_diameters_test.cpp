// Maximum 2D diameters against hand-measured shapes on axis-aligned and oblique grids.
#include "core/features/maximum_2d_diameters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/primitives.h"
#include "core/io/marching_cubes.h"

namespace soiq {
namespace {

TEST(Maximum2DDiameters, SingleVoxelOctahedronOnAnisotropicGrid) {
  // marching_cubes of one voxel: vertices at +-1/2 voxel along each axis. The plane k = 0 holds
  // (+-0.5 sx, 0) and (0, +-0.5 sy) in mm; the planes k = +-1/2 hold one vertex each.
  Mask m;
  m.geometry.dims = {1, 1, 1};
  m.geometry.spacing_mm = {1, 2, 3};
  m.voxels = {1};
  const auto mesh = marching_cubes(m);
  ASSERT_TRUE(mesh.ok());
  const auto d = maximum_2d_diameters(*mesh, m.geometry);
  ASSERT_TRUE(d.ok()) << d.status().to_string();
  EXPECT_DOUBLE_EQ(d->slice_mm, 2);   // max(1, 2, hypot(0.5, 1))
  EXPECT_DOUBLE_EQ(d->column_mm, 3);  // (+-0.5, 0), (0, +-1.5)
  EXPECT_DOUBLE_EQ(d->row_mm, 3);     // (+-1, 0), (0, +-1.5)
}

TEST(Maximum2DDiameters, BoxCornersOnHalfIndexPlanes) {
  // Corners at half-integer indices: each face plane holds a rectangle whose diagonal is the
  // diameter; the 3 x 2 x 1 box gives sqrt(13), sqrt(10), sqrt(5).
  ImageGeometry g;
  g.dims = {4, 3, 2};
  const auto d = maximum_2d_diameters(box({-0.5, -0.5, -0.5}, {2.5, 1.5, 0.5}), g);
  ASSERT_TRUE(d.ok());
  EXPECT_DOUBLE_EQ(d->slice_mm, std::sqrt(13.0));
  EXPECT_DOUBLE_EQ(d->column_mm, std::sqrt(10.0));
  EXPECT_DOUBLE_EQ(d->row_mm, std::sqrt(5.0));
}

TEST(Maximum2DDiameters, ObliqueGridMeasuresInItsOwnPlanes) {
  // The same box carried by a rotation together with its grid keeps its diameters (to rounding).
  const double c = std::cos(0.7), s = std::sin(0.7);
  const Mat3 r{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  ImageGeometry g;
  g.dims = {4, 3, 2};
  g.direction = r;
  g.origin_mm = {10, -20, 5};
  TriangleMesh mesh = box({-0.5, -0.5, -0.5}, {2.5, 1.5, 0.5});
  for (auto& v : mesh.vertices_mm) v = g.origin_mm + mul(r, v);
  const auto d = maximum_2d_diameters(mesh, g);
  ASSERT_TRUE(d.ok());
  EXPECT_NEAR(d->slice_mm, std::sqrt(13.0), 1e-12);
  EXPECT_NEAR(d->column_mm, std::sqrt(10.0), 1e-12);
  EXPECT_NEAR(d->row_mm, std::sqrt(5.0), 1e-12);
}

TEST(Maximum2DDiameters, EmptyMeshIsInvalidArgument) {
  const auto d = maximum_2d_diameters(TriangleMesh{}, ImageGeometry{});
  EXPECT_EQ(d.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(d.status().message().find("empty mesh"), std::string::npos);
}

TEST(Maximum2DDiameters, NonFiniteVertexIsInvalidArgument) {
  TriangleMesh mesh = box({0, 0, 0}, {1, 1, 1});
  mesh.vertices_mm[3][1] = INFINITY;
  ImageGeometry g;
  g.dims = {2, 2, 2};
  const auto d = maximum_2d_diameters(mesh, g);
  EXPECT_EQ(d.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(d.status().message().find("vertex 3"), std::string::npos);
}

TEST(Maximum2DDiameters, InvalidGridIsInvalidArgument) {
  ImageGeometry g;
  g.spacing_mm = {1, -1, 1};
  EXPECT_EQ(maximum_2d_diameters(box({0, 0, 0}, {1, 1, 1}), g).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
