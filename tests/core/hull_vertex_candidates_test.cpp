// The hull shortlist against brute force: on random clouds (general position, lattices with many
// coplanar and collinear points, exact duplicates, flat slabs) the shortlist's hull is the whole
// set's hull, and the farthest pair over it is the all-pairs one.
#include "core/geometry/hull_vertex_candidates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "core/geometry/convex_hull.h"

namespace soiq {
namespace {

std::vector<Vec3> subset(const std::vector<Vec3>& points, const std::vector<int64_t>& indices) {
  std::vector<Vec3> out;
  for (const int64_t i : indices) out.push_back(points[size_t(i)]);
  return out;
}

std::set<Vec3> hull_vertex_positions(const std::vector<Vec3>& points, const ConvexHull& hull) {
  std::set<Vec3> out;
  for (const int64_t v : hull.vertex_indices) out.insert(points[size_t(v)]);
  return out;
}

double all_pairs_squared_diameter(const std::vector<Vec3>& p) {
  double best = 0;
  for (size_t a = 0; a < p.size(); ++a) {
    for (size_t b = a + 1; b < p.size(); ++b) best = std::max(best, dot(p[a] - p[b], p[a] - p[b]));
  }
  return best;
}

// Random clouds of one kind: 0 general position; 1 a lattice ball (coplanar rows and planes); 2 a
// lattice box with duplicates; 3 a thin lattice slab (two planes); 4 a half-unit lattice shell;
// 5 that shell moved far off the origin, out of the small dyadic lattice (dyadic_lattice.h), so
// the sorting path runs instead of the dense tables.
std::vector<Vec3> cloud(int kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> real(-10, 10);
  std::uniform_int_distribution<int> cell(-6, 6);
  std::vector<Vec3> p;
  const int n = 400 + int(rng() % 600);
  while (int(p.size()) < n) {
    if (kind == 0) {
      p.push_back({real(rng), real(rng), real(rng)});
      continue;
    }
    const Vec3 q{double(cell(rng)), double(cell(rng)), double(kind == 3 ? cell(rng) % 2 : cell(rng))};
    if (kind == 1 && dot(q, q) > 30) continue;
    if (kind >= 4) {
      const Vec3 h = 0.5 * q;
      if (dot(h, h) < 6 || dot(h, h) > 9) continue;
      p.push_back(kind == 5 ? h + Vec3{40000.25, -70000.5, 12345.75} : h);
      continue;
    }
    p.push_back(q);
    if (kind == 2 && rng() % 4 == 0) p.push_back(q);  // an exact duplicate
  }
  std::shuffle(p.begin(), p.end(), rng);
  return p;
}

TEST(HullVertexCandidates, ShortlistHasTheSameHullAndDiameterAsTheWholeCloud) {
  std::mt19937_64 rng(11);
  for (int kind = 0; kind < 6; ++kind) {
    for (int trial = 0; trial < 8; ++trial) {
      const std::vector<Vec3> points = cloud(kind, rng);
      const std::vector<int64_t> kept = hull_vertex_candidates(points);
      ASSERT_TRUE(std::is_sorted(kept.begin(), kept.end()));
      const std::vector<Vec3> shortlist = subset(points, kept);
      const auto all = convex_hull(points);
      const auto some = convex_hull(shortlist);
      ASSERT_TRUE(all.ok() && some.ok()) << "kind " << kind;
      EXPECT_EQ(hull_vertex_positions(points, *all), hull_vertex_positions(shortlist, *some)) << "kind " << kind;
      // Volume and area are sums over different triangulations of one polytope: equal to rounding.
      EXPECT_NEAR(some->volume_mm3, all->volume_mm3, 1e-12 * all->volume_mm3) << "kind " << kind;
      EXPECT_NEAR(some->area_mm2, all->area_mm2, 1e-12 * all->area_mm2) << "kind " << kind;
      // Every extreme point survives, so the farthest pair does: the same doubles, exactly.
      EXPECT_EQ(all_pairs_squared_diameter(shortlist), all_pairs_squared_diameter(points)) << "kind " << kind;
      // No position is listed twice.
      EXPECT_EQ(std::set<Vec3>(shortlist.begin(), shortlist.end()).size(), shortlist.size());
      if (kind == 0) {
        EXPECT_EQ(kept.size(), points.size());  // general position: one point per plane, all kept
      } else {
        EXPECT_LT(kept.size(), points.size() / 2) << "kind " << kind;
      }
    }
  }
}

TEST(HullVertexCandidates, LatticeCubeKeepsOnlyItsEightCorners) {
  std::vector<Vec3> points;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) points.push_back({0.5 * i, 0.5 * j, 0.5 * k});
  const std::vector<int64_t> kept = hull_vertex_candidates(points);
  ASSERT_EQ(kept.size(), 8u);
  for (const int64_t v : kept) {
    for (int a = 0; a < 3; ++a) EXPECT_TRUE(points[size_t(v)][a] == 0 || points[size_t(v)][a] == 2);
  }
}

TEST(HullVertexCandidates, DuplicatesKeepTheirLowestIndexOnly) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, 0}};
  EXPECT_EQ(hull_vertex_candidates(points), (std::vector<int64_t>{0, 1, 2, 3}));  // dense tables
  std::vector<Vec3> off_lattice = points;  // 0.1 is no dyadic number: the sorting path
  for (Vec3& p : off_lattice) p = p + Vec3{0.1, 0.1, 0.1};
  EXPECT_EQ(hull_vertex_candidates(off_lattice), (std::vector<int64_t>{0, 1, 2, 3}));
}

TEST(HullVertexCandidates, CoplanarSetKeepsItsPolygonCorners) {
  std::vector<Vec3> points;
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i) points.push_back({double(i), double(j), 2.0});
  EXPECT_EQ(hull_vertex_candidates(points).size(), 4u);
  for (Vec3& p : points) p = p + Vec3{0.1, 0.1, 0.1};
  EXPECT_EQ(hull_vertex_candidates(points).size(), 4u);
  EXPECT_TRUE(hull_vertex_candidates({}).empty());
}

}  // namespace
}  // namespace soiq
