// The hull's output pinned to the last bit: the triangles in order (a hash), the corner count and
// the volume and area as exact doubles, on point sets of each kind the hull meets (general
// position, all on a sphere, the half-voxel lattice with ties and duplicates, the lattice scaled and
// moved off it so the exact predicates decide the ties). The volume and area are sums over the
// triangles in the order the Quickhull leaves them, so a change to the order of its work (which
// face a point waits on, which point comes next) moves them in the last bits; the densities that
// divide by them would then move too. The values are
// those of the one-point-at-a-time Quickhull with linked outside sets that the hull began as.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/geometry/convex_hull.h"

namespace soiq {
namespace {

// A fixed sequence of uniform doubles in [0, 1) (SplitMix64), the same on every standard library.
struct SplitMix {
  uint64_t state;
  double next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
};

std::vector<Vec3> point_set(int kind) {
  SplitMix rng{uint64_t(kind) + 1};
  std::vector<Vec3> p;
  for (int i = 0; i < 6000; ++i) {
    Vec3 q{rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5};
    if (kind == 0) {
      p.push_back(100.0 * q + Vec3{3, -40, 250});  // general position
    } else if (kind == 1) {
      p.push_back((30.0 / norm(q)) * q);  // on a sphere, rounded: nearly every point a corner
    } else {
      // The half-voxel lattice in a ball (many coplanar corners, duplicates); kind 3 scaled by 0.1
      // (planes within an ulp of their points, the filter's undecided cases), kind 4 moved off the
      // lattice fast path's range.
      const Vec3 cell{std::floor(24 * q[0]) / 2, std::floor(24 * q[1]) / 2, std::floor(24 * q[2]) / 2};
      if (dot(cell, cell) > 36) continue;
      p.push_back(kind == 2 ? cell : kind == 3 ? 0.1 * cell : cell + Vec3{40000.25, -70000.5, 12345.75});
    }
  }
  return p;
}

uint64_t triangles_hash(const ConvexHull& hull) {  // FNV-1a over the indices, in order
  uint64_t h = 0xcbf29ce484222325ull;
  for (const auto& t : hull.triangles) {
    for (const int64_t v : t) h = (h ^ uint64_t(v)) * 0x100000001b3ull;
  }
  return h;
}

struct Pinned {
  size_t corners, triangles;
  uint64_t hash;
  double volume, area;
};

TEST(ConvexHullBits, OutputIsPinnedToTheLastBit) {
  const Pinned expected[] = {
      {125, 246, 0xfaf68ceb0db97766ull, 0x1.dd4c0a00bcdfcp+19, 0x1.b970ea7fd3da7p+15},
      {6000, 11996, 0x5c95abb1d4a9433dull, 0x1.b8c27d7e6a6fep+16, 0x1.610507674d91cp+13},
      {168, 450, 0x91c74720827d7e1aull, 0x1.921aaaaaaaaabp+9, 0x1.a77f87d6d5d49p+8},
      {191, 488, 0xd6a5cd31e2c45d3cull, 0x1.9c15d867c3ec8p-1, 0x1.0f723f1ed0aeap+2},
      {176, 460, 0x88a4ea177ebee80eull, 0x1.9312aaaaaaab5p+9, 0x1.a8390d28e5cdfp+8},
  };
  for (int kind = 0; kind < 5; ++kind) {
    const auto points = point_set(kind);
    const auto hull = convex_hull(points);
    ASSERT_TRUE(hull.ok()) << hull.status().to_string();
    const Pinned& e = expected[kind];
    EXPECT_EQ(hull->vertex_indices.size(), e.corners) << "kind " << kind;
    EXPECT_EQ(hull->triangles.size(), e.triangles) << "kind " << kind;
    EXPECT_EQ(triangles_hash(*hull), e.hash) << "kind " << kind;
    EXPECT_EQ(hull->volume_mm3, e.volume) << "kind " << kind;
    EXPECT_EQ(hull->area_mm2, e.area) << "kind " << kind;
  }
}

}  // namespace
}  // namespace soiq
