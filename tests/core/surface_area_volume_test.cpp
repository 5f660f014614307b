// Area and volume of hand-measurable solids, far from the origin too; bitwise agreement with
// surface_shape (the service's hull-free path relies on it); and the error paths.
#include "core/geometry/surface_area_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/features/surface_shape.h"
#include "core/geometry/mesh_defects.h"
#include "core/geometry/primitives.h"

namespace soiq {
namespace {

TEST(SurfaceAreaVolume, BoxFarFromTheOrigin) {
  // 2 x 3 x 4 mm at scanner coordinates: the tetrahedra against the first vertex keep it exact
  // to rounding where tetrahedra against the origin would cancel.
  const auto m = surface_area_volume(box({-400.5, 300.25, 1200}, {-398.5, 303.25, 1204}));
  ASSERT_TRUE(m.ok()) << m.status().to_string();
  EXPECT_NEAR(m->volume_mm3, 24, 1e-12);
  EXPECT_NEAR(m->area_mm2, 52, 1e-12);
  EXPECT_EQ(m->used, std::vector<uint8_t>(8, 1));
}

TEST(SurfaceAreaVolume, SphereConvergesToAnalytic) {
  // A uv sphere inscribed in the sphere of radius 10: volume and area below the analytic values,
  // within the relative error of its 100 x 200 facets (about 1e-3).
  const auto m = surface_area_volume(uv_sphere({1, 2, 3}, 10, 100, 200));
  ASSERT_TRUE(m.ok());
  const double pi = std::numbers::pi;
  EXPECT_LT(m->volume_mm3, 4.0 / 3 * pi * 1000);
  EXPECT_NEAR(m->volume_mm3, 4.0 / 3 * pi * 1000, 2e-3 * 4.0 / 3 * pi * 1000);
  EXPECT_NEAR(m->area_mm2, 4 * pi * 100, 2e-3 * 4 * pi * 100);
  EXPECT_NEAR(m->volume_mm3, signed_volume_mm3(uv_sphere({1, 2, 3}, 10, 100, 200)), 1e-9 * m->volume_mm3);
}

TEST(SurfaceAreaVolume, SurfaceShapeUsesTheseDoublesBitForBit) {
  const TriangleMesh mesh = torus({-120.3, 45.7, 300.1}, 20, 7, 48, 24);
  const auto m = surface_area_volume(mesh);
  const auto s = surface_shape(mesh);
  ASSERT_TRUE(m.ok() && s.ok());
  EXPECT_EQ(s->mesh_volume_mm3, m->volume_mm3);
  EXPECT_EQ(s->surface_area_mm2, m->area_mm2);
}

TEST(SurfaceAreaVolume, UnusedVerticesAreMarked) {
  TriangleMesh mesh = box({0, 0, 0}, {1, 1, 1});
  mesh.vertices_mm.push_back({NAN, 0, 0});  // unused: ignored
  const auto m = surface_area_volume(mesh);
  ASSERT_TRUE(m.ok()) << m.status().to_string();
  EXPECT_EQ(m->used.back(), 0);
}

TEST(SurfaceAreaVolume, BadMeshesAreInvalidArgument) {
  EXPECT_EQ(surface_area_volume(TriangleMesh{}).status().code(), StatusCode::kInvalidArgument);
  TriangleMesh out_of_range = box({0, 0, 0}, {1, 1, 1});
  out_of_range.triangles[3][1] = 8;
  const auto r = surface_area_volume(out_of_range);
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("triangle 3 has vertex index 8"), std::string::npos) << r.status().message();
  TriangleMesh non_finite = box({0, 0, 0}, {1, 1, 1});
  non_finite.vertices_mm[5][2] = INFINITY;
  const auto f = surface_area_volume(non_finite);
  EXPECT_NE(f.status().message().find("mesh vertex 5 has a non-finite coordinate"), std::string::npos)
      << f.status().message();
  const auto inward = surface_area_volume(flipped(box({0, 0, 0}, {1, 1, 1})));
  EXPECT_EQ(inward.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(inward.status().message().find("inward-facing"), std::string::npos);
}

}  // namespace
}  // namespace soiq
