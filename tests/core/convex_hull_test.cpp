// Convex hulls against hand-known polytopes, containment of random clouds and Qhull's error paths.
#include "core/convex_hull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace soiq {
namespace {

std::vector<Vec3> lattice(int n, double step) {  // (n+1)^3 points, many coplanar on the faces
  std::vector<Vec3> p;
  for (int k = 0; k <= n; ++k) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) p.push_back({i * step, j * step, k * step});
    }
  }
  return p;
}

TEST(ConvexHull, CubeWithInteriorAndFacePointsKeepsOnlyTheCorners) {
  const auto points = lattice(4, 0.5);  // cube of side 2
  const auto hull = convex_hull(points);
  ASSERT_TRUE(hull.ok()) << hull.status().to_string();
  EXPECT_EQ(hull->vertex_indices.size(), 8u);
  for (const int64_t v : hull->vertex_indices) {
    for (int a = 0; a < 3; ++a) EXPECT_TRUE(points[v][a] == 0 || points[v][a] == 2);
  }
  EXPECT_NEAR(hull->volume_mm3, 8, 1e-12);
  EXPECT_NEAR(hull->area_mm2, 24, 1e-12);
}

TEST(ConvexHull, TrianglesFaceOutward) {
  const auto points = lattice(2, 1.0);
  const auto hull = convex_hull(points);
  ASSERT_TRUE(hull.ok());
  const Vec3 centre{1, 1, 1};
  for (const auto& t : hull->triangles) {
    const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
    EXPECT_GT(dot(n, points[t[0]] - centre), 0);
  }
}

TEST(ConvexHull, OctahedronHasKnownVolumeAndArea) {
  // |x|+|y|+|z| <= 1: volume 4/3, area 8 equilateral triangles of side sqrt(2).
  const std::vector<Vec3> points{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 0, 0}};
  const auto hull = convex_hull(points);
  ASSERT_TRUE(hull.ok());
  EXPECT_EQ(hull->vertex_indices, (std::vector<int64_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_NEAR(hull->volume_mm3, 4.0 / 3, 1e-14);
  EXPECT_NEAR(hull->area_mm2, 8 * std::sqrt(3.0) / 4 * 2, 1e-14);
  EXPECT_EQ(hull->triangles.size(), 8u);
}

TEST(ConvexHull, RandomCloudLiesInsideItsHull) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0, 10);
  std::vector<Vec3> points(2000);
  for (auto& p : points) p = {gauss(rng), gauss(rng), gauss(rng) + 100};
  const auto hull = convex_hull(points);
  ASSERT_TRUE(hull.ok());
  for (const auto& t : hull->triangles) {
    const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
    const double scale = norm(n) * 1e-9;  // Qhull's round-off is ~1e-13 of the coordinates
    for (const auto& p : points) ASSERT_LE(dot(n, p - points[t[0]]), scale);
  }
}

TEST(ConvexHull, CoplanarPointsAreInvalidArgumentAndQhullStaysQuiet) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  testing::internal::CaptureStderr();
  const auto hull = convex_hull(square);
  const std::string printed = testing::internal::GetCapturedStderr();
  ASSERT_FALSE(hull.ok());
  EXPECT_EQ(hull.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hull.status().message().find("degenerate"), std::string::npos) << hull.status().message();
  EXPECT_NE(hull.status().message().find("QH"), std::string::npos) << hull.status().message();
  EXPECT_EQ(printed, "");
}

TEST(ConvexHull, CollinearPointsAreInvalidArgument) {
  const std::vector<Vec3> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {4, 4, 4}};
  EXPECT_EQ(convex_hull(line).status().code(), StatusCode::kInvalidArgument);
}

TEST(ConvexHull, FewerThanFourPointsAreInvalidArgument) {
  const auto hull = convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  EXPECT_EQ(hull.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hull.status().message().find("at least 4"), std::string::npos);
}

TEST(ConvexHull, NonFiniteCoordinateIsInvalidArgument) {
  const auto hull = convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}});
  EXPECT_EQ(hull.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hull.status().message().find("point 3"), std::string::npos);
}

TEST(ConvexHull, RepeatedCallsAreIndependent) {
  // One Qhull context per call: a failed call leaves nothing behind for the next one.
  ASSERT_FALSE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}).ok());
  const auto hull = convex_hull(lattice(1, 3.0));
  ASSERT_TRUE(hull.ok());
  EXPECT_NEAR(hull->volume_mm3, 27, 1e-12);
}

}  // namespace
}  // namespace soiq
