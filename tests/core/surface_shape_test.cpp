// Surface shape features of hand-measurable solids and the error paths.
#include "core/features/surface_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/geometry/primitives.h"

namespace soiq {
namespace {

TEST(SurfaceShape, BoxHasHandComputedFeatures) {
  const auto s = surface_shape(box({1, 2, 3}, {3, 5, 7}));  // 2 x 3 x 4 mm
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  const double v = 24, a = 52;
  EXPECT_NEAR(s->mesh_volume_mm3, v, 1e-12);
  EXPECT_NEAR(s->surface_area_mm2, a, 1e-12);
  EXPECT_NEAR(s->surface_volume_ratio, a / v, 1e-14);
  EXPECT_NEAR(s->sphericity, std::cbrt(36 * std::numbers::pi * v * v) / a, 1e-14);
  EXPECT_NEAR(s->spherical_disproportion, a / std::cbrt(36 * std::numbers::pi * v * v), 1e-14);
  EXPECT_NEAR(s->asphericity, std::cbrt(a * a * a / (36 * std::numbers::pi * v * v)) - 1, 1e-14);
  EXPECT_NEAR(s->compactness_1, v / std::sqrt(std::numbers::pi * a * a * a), 1e-14);
  EXPECT_NEAR(s->compactness_2, 36 * std::numbers::pi * v * v / (a * a * a), 1e-14);
  EXPECT_NEAR(s->maximum_3d_diameter_mm, std::sqrt(29.0), 1e-14);
  // A box is its own bounding box and its own hull.
  EXPECT_NEAR(s->volume_density_aabb, 1, 1e-14);
  EXPECT_NEAR(s->area_density_aabb, 1, 1e-14);
  EXPECT_NEAR(s->volume_density_convex_hull, 1, 1e-12);
  EXPECT_NEAR(s->area_density_convex_hull, 1, 1e-12);
}

TEST(SurfaceShape, SphericityRelationsHold) {
  // IBSI: compactness 2 = sphericity^3, spherical disproportion = 1 / sphericity,
  // asphericity = 1 / sphericity - 1, compactness 1 = sqrt(compactness 2) / (6 pi).
  const auto s = surface_shape(torus({0, 0, 0}, 10, 3, 48, 24));
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(s->compactness_2, std::pow(s->sphericity, 3), 1e-14);
  EXPECT_NEAR(s->spherical_disproportion, 1 / s->sphericity, 1e-14);
  EXPECT_NEAR(s->asphericity, 1 / s->sphericity - 1, 1e-14);
  EXPECT_NEAR(s->compactness_1, std::sqrt(s->compactness_2) / (6 * std::numbers::pi), 1e-14);
  EXPECT_LT(s->volume_density_convex_hull, 1);  // the hole is in the hull, not in the torus
}

TEST(SurfaceShape, BoundingBoxUsesTheGivenAxes) {
  // A cube rotated by 45 degrees about z: its LPS box is larger, its own-axes box is itself.
  const double c = std::sqrt(0.5);
  const Mat3 r{{{c, -c, 0}, {c, c, 0}, {0, 0, 1}}};
  TriangleMesh cube = box({-1, -1, -1}, {1, 1, 1});
  for (auto& v : cube.vertices_mm) v = mul(r, v);
  const auto lps = surface_shape(cube);
  const auto own = surface_shape(cube, r);
  ASSERT_TRUE(lps.ok() && own.ok());
  EXPECT_NEAR(lps->volume_density_aabb, 8 / (2 * std::sqrt(8.0) * std::sqrt(8.0)), 1e-12);
  EXPECT_NEAR(own->volume_density_aabb, 1, 1e-12);
  EXPECT_NEAR(own->area_density_aabb, 1, 1e-12);
}

TEST(SurfaceShape, InwardFacingMeshIsInvalidArgument) {
  const auto s = surface_shape(flipped(box({0, 0, 0}, {1, 1, 1})));
  EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.status().message().find("orient_outward"), std::string::npos);
}

TEST(SurfaceShape, MeshWithoutTrianglesIsInvalidArgument) {
  EXPECT_EQ(surface_shape(TriangleMesh{}).status().code(), StatusCode::kInvalidArgument);
}

TEST(SurfaceShape, IndexOutOfRangeIsInvalidArgument) {
  TriangleMesh m = box({0, 0, 0}, {1, 1, 1});
  m.triangles[5][2] = 8;
  const auto s = surface_shape(m);
  EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.status().message().find("triangle 5"), std::string::npos);
}

TEST(SurfaceShape, NonFiniteVertexIsInvalidArgument) {
  TriangleMesh m = box({0, 0, 0}, {1, 1, 1});
  m.vertices_mm[2][0] = NAN;
  EXPECT_EQ(surface_shape(m).status().code(), StatusCode::kInvalidArgument);
}

TEST(SurfaceShape, FlatDoubleSidedSheetIsInvalidArgument) {
  // Two triangles back to back enclose nothing.
  const TriangleMesh sheet{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 1}}};
  EXPECT_EQ(surface_shape(sheet).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
