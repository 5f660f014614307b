// Convex hulls against hand-known polytopes, exact containment and exact corners on random and
// lattice clouds, Qhull as an independent oracle, and the error paths.
#include "core/geometry/convex_hull.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "core/reference/qhull_convex_hull.h"

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

// The sign of det[b - a; c - a; d - a] in exact rationals (GMP): independent of the hull's own
// floating-point filter and expansions.
int exact_orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  mpq_class u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i)
    u[i] = mpq_class(b[i]) - a[i], v[i] = mpq_class(c[i]) - a[i], w[i] = mpq_class(d[i]) - a[i];
  const mpq_class det =
      u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
  return sgn(det);
}

// Checks, exactly, that every point lies on or below every triangle (so the triangles, facing
// outward, bound a polytope holding the set), that each triangle is proper, that the surface closes
// up (each directed edge once, and its reverse once), and that the listed vertices are distinct
// positions on the surface, ascending. Which positions they are is checked against
// brute_force_corners.
void expect_exact_hull(const std::vector<Vec3>& points, const ConvexHull& hull) {
  std::set<std::pair<int64_t, int64_t>> edges;
  std::set<int64_t> on_hull;
  for (const auto& t : hull.triangles) {
    const Vec3 &a = points[size_t(t[0])], &b = points[size_t(t[1])], &c = points[size_t(t[2])];
    ASSERT_GT(norm(cross(b - a, c - a)), 0) << "degenerate hull triangle";
    for (const Vec3& p : points) ASSERT_LE(exact_orient(a, b, c, p), 0) << "a point lies outside a hull triangle";
    for (int e = 0; e < 3; ++e) {
      ASSERT_TRUE(edges.insert({t[size_t(e)], t[size_t((e + 1) % 3)]}).second) << "directed edge used twice";
      on_hull.insert(t[size_t(e)]);
    }
  }
  for (const auto& [u, w] : edges) ASSERT_TRUE(edges.count({w, u})) << "hull surface is not closed";
  for (const int64_t v : hull.vertex_indices) ASSERT_TRUE(on_hull.count(v)) << "vertex " << v << " is on no triangle";
  std::set<Vec3> positions;
  for (const int64_t v : hull.vertex_indices) {
    ASSERT_TRUE(positions.insert(points[size_t(v)]).second) << "a position is listed twice";
  }
  ASSERT_TRUE(std::is_sorted(hull.vertex_indices.begin(), hull.vertex_indices.end()));
}

// The corners of conv(points) by brute force: a distinct position p is a corner iff it lies
// outside the hull of all the other positions, i.e. strictly above one of that hull's triangles
// (Qhull's triangles, the side decided in exact rationals; Qhull may drop a point within its
// round-off of a facet, which on these sets' exact ties never decides a corner). O(n) hulls.
std::set<Vec3> brute_force_corners(const std::vector<Vec3>& points) {
  std::set<Vec3> corners;
  const std::set<Vec3> distinct(points.begin(), points.end());
  const std::vector<Vec3> unique(distinct.begin(), distinct.end());
  for (size_t i = 0; i < unique.size(); ++i) {
    std::vector<Vec3> others = unique;
    others.erase(others.begin() + long(i));
    const auto hull = qhull_convex_hull(others);  // the oracle's triangles, checked exactly below
    bool inside = hull.ok();
    if (inside) {
      for (const auto& t : hull->triangles) {
        if (exact_orient(others[size_t(t[0])], others[size_t(t[1])], others[size_t(t[2])], unique[i]) > 0)
          inside = false;
      }
    }
    if (!inside) corners.insert(unique[i]);
  }
  return corners;
}

std::set<Vec3> corner_positions(const std::vector<Vec3>& points, const ConvexHull& hull) {
  std::set<Vec3> out;
  for (const int64_t v : hull.vertex_indices) out.insert(points[size_t(v)]);
  return out;
}

std::vector<Vec3> cloud(int kind, std::mt19937_64& rng, int n) {
  std::normal_distribution<double> gauss(0, 10);
  std::uniform_int_distribution<int> cell(-6, 6);
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    if (kind == 0) {
      p.push_back({gauss(rng), gauss(rng), gauss(rng) + 100});  // general position
    } else if (kind == 1) {
      p.push_back({0.5 * cell(rng), 0.5 * cell(rng), 0.5 * cell(rng)});  // lattice, many ties and duplicates
    } else {
      // A lattice ball, the shape of a marching-cubes mesh: many coplanar corners. Kind 3 moves it
      // far off the origin, past the lattice fast path's range: the filtered, expansion-backed
      // predicates decide the same ties.
      const Vec3 q{0.5 * cell(rng), 0.5 * cell(rng), 0.5 * cell(rng)};
      const Vec3 offset = kind == 3 ? Vec3{40000.25, -70000.5, 12345.75} : Vec3{0, 0, 0};
      // Kind 4 scales it by 0.1: rounded, the lattice's planes hold points within an ulp of
      // coplanar, the cases the hull's floating-point filter must hand to the exact predicate.
      if (dot(q, q) <= 9) p.push_back(kind == 4 ? 0.1 * q : q + offset);
    }
  }
  return p;
}

TEST(ConvexHull, HullIsExactOnRandomAndLatticeClouds) {
  std::mt19937_64 rng(7);
  for (int kind = 0; kind < 5; ++kind) {
    for (int trial = 0; trial < 4; ++trial) {
      const std::vector<Vec3> points = cloud(kind, rng, 300);
      const auto hull = convex_hull(points);
      ASSERT_TRUE(hull.ok()) << hull.status().to_string();
      expect_exact_hull(points, *hull);
      // Qhull's round-off can misjudge the near-ties of kind 4: there the exact checks above stand.
      if (kind == 4) continue;
      EXPECT_EQ(corner_positions(points, *hull), brute_force_corners(points)) << "kind " << kind;
    }
  }
}

TEST(ConvexHull, AgreesWithQhullOnLargeClouds) {
  std::mt19937_64 rng(8);
  for (int kind = 0; kind < 4; ++kind) {
    const std::vector<Vec3> points = cloud(kind, rng, 20000);
    const auto ours = convex_hull(points);
    const auto theirs = qhull_convex_hull(points);
    ASSERT_TRUE(ours.ok() && theirs.ok());
    // Different triangulations of one polytope: equal to rounding. Qhull's vertices are within its
    // round-off of ours; on lattices (exact ties) they are the same corners.
    EXPECT_NEAR(ours->volume_mm3, theirs->volume_mm3, 1e-12 * theirs->volume_mm3) << "kind " << kind;
    EXPECT_NEAR(ours->area_mm2, theirs->area_mm2, 1e-12 * theirs->area_mm2) << "kind " << kind;
    if (kind > 0) {
      EXPECT_EQ(corner_positions(points, *ours), corner_positions(points, *theirs)) << "kind " << kind;
    }
  }
}

TEST(ConvexHull, CoplanarPointsAreInvalidArgument) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  const auto hull = convex_hull(square);
  ASSERT_FALSE(hull.ok());
  EXPECT_EQ(hull.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hull.status().message().find("coplanar"), std::string::npos) << hull.status().message();
}

TEST(ConvexHull, CoincidentPointsAreInvalidArgument) {
  const auto hull = convex_hull({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}});
  EXPECT_EQ(hull.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hull.status().message().find("coincide"), std::string::npos) << hull.status().message();
}

TEST(ConvexHull, QhullOracleNamesItsErrorAndStaysQuiet) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  testing::internal::CaptureStderr();
  const auto hull = qhull_convex_hull(square);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_FALSE(hull.ok());
  EXPECT_EQ(hull.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(hull.status().message().find("QH"), std::string::npos) << hull.status().message();
}

TEST(ConvexHull, CollinearPointsAreInvalidArgument) {
  const std::vector<Vec3> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {4, 4, 4}};
  EXPECT_EQ(convex_hull(line).status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(convex_hull(line).status().message().find("collinear"), std::string::npos);
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
  // No state outlives a call: a failed call leaves nothing behind for the next one.
  ASSERT_FALSE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}).ok());
  const auto hull = convex_hull(lattice(1, 3.0));
  ASSERT_TRUE(hull.ok());
  EXPECT_NEAR(hull->volume_mm3, 27, 1e-12);
}

}  // namespace
}  // namespace soiq
