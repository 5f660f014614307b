// The 1D method equals the paper's 3D method (core/reference/voxelize_3d_raycast: per-voxel rays,
// written independently) voxel for voxel, over shapes, poses, grids and degenerate alignments.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <random>
#include <string>

#include "core/geometry/primitives.h"
#include "core/reference/voxelize_3d_raycast.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

struct Case {
  std::string name;
  TriangleMesh mesh;
  ImageGeometry grid;
  FillRule rule = FillRule::kNonZero;
};

// GoogleTest prints parameters in test listings: the name, not 232 bytes of hex.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

ImageGeometry grid(int64_t nx, int64_t ny, int64_t nz, Vec3 spacing = {1, 1, 1}, Vec3 origin = {0, 0, 0}) {
  ImageGeometry g;
  g.dims = {nx, ny, nz};
  g.spacing_mm = spacing;
  g.origin_mm = origin;
  return g;
}

// A uniformly random rotation (from a random unit quaternion).
Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  double q[4];
  double len = 0;
  for (double& c : q) {
    c = n(rng);
    len += c * c;
  }
  len = std::sqrt(len);
  for (double& c : q) c /= len;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

// Moves a mesh rigidly: p -> R p + t.
TriangleMesh moved(const TriangleMesh& m, const Mat3& r, const Vec3& t) {
  TriangleMesh out = m;
  for (Vec3& p : out.vertices_mm) p = mul(r, p) + t;
  return out;
}

// A mesh whose vertices are snapped to the integer lattice of an identity grid: vertices on voxel
// centres, edges along row lines, faces containing rows. Snapping keeps it closed.
TriangleMesh snapped(const TriangleMesh& m) {
  TriangleMesh out = m;
  for (Vec3& p : out.vertices_mm) {
    for (double& c : p) c = std::round(c);
  }
  return out;
}

// An octahedron with all six vertices on voxel centres.
TriangleMesh octahedron(const Vec3& c, double r) {
  TriangleMesh m;
  m.vertices_mm = {c + Vec3{r, 0, 0},  c + Vec3{-r, 0, 0}, c + Vec3{0, r, 0},
                   c + Vec3{0, -r, 0}, c + Vec3{0, 0, r},  c + Vec3{0, 0, -r}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  orient_outward(m);
  return m;
}

std::vector<Case> cases() {
  std::vector<Case> cs;
  const Vec3 c{15.3, 14.8, 15.6};
  cs.push_back({"sphere", uv_sphere(c, 10, 24, 48), grid(32, 32, 32)});
  cs.push_back({"coarse_sphere", uv_sphere(c, 11, 5, 7), grid(32, 32, 32)});
  cs.push_back({"torus", torus(c, 10, 3.5, 48, 24), grid(32, 32, 32)});
  cs.push_back({"hollow_shell", merge(uv_sphere(c, 12, 24, 48), flipped(uv_sphere(c, 7, 16, 32))), grid(32, 32, 32)});
  cs.push_back({"overlapping_components",
                merge(uv_sphere(c, 8, 20, 40),
                      merge(torus(c + Vec3{3, 0, 0}, 9, 3, 40, 20), box({4.2, 5.1, 6.3}, {14.7, 13.9, 16.2}))),
                grid(32, 32, 32)});
  cs.push_back({"overlapping_components_even_odd",
                merge(uv_sphere(c, 8, 20, 40), torus(c + Vec3{3, 0, 0}, 9, 3, 40, 20)), grid(32, 32, 32),
                FillRule::kEvenOdd});
  cs.push_back({"anisotropic_spacing", uv_sphere(c, 10, 24, 48), grid(40, 20, 12, {0.75, 1.5, 2.5})});
  cs.push_back({"box_on_voxel_centres", box({3, 4, 5}, {20, 17, 25}), grid(32, 32, 32)});
  cs.push_back({"octahedron_on_voxel_centres", octahedron({16, 16, 16}, 9), grid(32, 32, 32)});
  cs.push_back({"snapped_sphere", snapped(uv_sphere({16, 16, 16}, 10, 12, 24)), grid(32, 32, 32)});
  cs.push_back({"snapped_torus", snapped(torus({16, 16, 16}, 9, 4, 20, 10)), grid(32, 32, 32)});
  // Coarse spheres with vertices exactly on voxel centres, where the crossing x must be the
  // vertex's x to the last bit for the half-open rule (found by the oracle).
  cs.push_back({"coarse_sphere_vertices_on_centres", uv_sphere({10, 10, 10}, 7, 8, 16), grid(21, 21, 21)});
  cs.push_back({"lattice_centred_sphere", uv_sphere({8, 8, 8}, 6, 4, 8), grid(17, 17, 17)});
  cs.push_back({"half_voxel_box", box({3.5, 4.5, 5.5}, {20.5, 17.5, 25.5}), grid(32, 32, 32)});
  cs.push_back({"grid_cuts_mesh", uv_sphere(c, 10, 24, 48), grid(20, 32, 25, {1, 1, 1}, {-2, 3, 1})});
  cs.push_back({"grid_misses_mesh", uv_sphere(c, 10, 24, 48), grid(10, 10, 10, {1, 1, 1}, {100, 0, 0})});
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int i = 0; i < 8; ++i) {
    // The mesh under a random rigid motion, on a grid with a random direction matrix, origin and
    // anisotropic spacing.
    const TriangleMesh base = i % 2 ? torus({0, 0, 0}, 9, 3.5, 40, 20)
                                    : merge(uv_sphere({0, 0, 0}, 9, 20, 40), flipped(uv_sphere({1, 0, 0}, 4, 12, 24)));
    ImageGeometry g = grid(36, 36, 36, {0.8 + 0.1 * i, 0.9, 1.0 + 0.05 * i});
    g.direction = random_rotation(rng);
    g.origin_mm = {u(rng), u(rng), u(rng)};
    const Vec3 centre = g.index_to_physical({17.5 + u(rng), 17.5 + u(rng), 17.5 + u(rng)});
    cs.push_back({"random_pose_" + std::to_string(i), moved(base, random_rotation(rng), centre), g});
  }
  return cs;
}

class Voxelize1DOracle : public ::testing::TestWithParam<Case> {};

TEST_P(Voxelize1DOracle, EqualsThe3DRaycastVoxelForVoxel) {
  const Case& c = GetParam();
  VoxelizeOptions o;
  o.fill_rule = c.rule;
  auto ours = voxelize_1d(c.mesh, c.grid, o);
  ASSERT_TRUE(ours.ok()) << ours.status().to_string();
  auto oracle = voxelize_3d_raycast(c.mesh, c.grid, c.rule);
  ASSERT_TRUE(oracle.ok()) << oracle.status().to_string();
  auto cmp = compare(ours->volume, *oracle);
  ASSERT_TRUE(cmp.ok());
  EXPECT_EQ(cmp->only_a, 0) << c.name;
  EXPECT_EQ(cmp->only_b, 0) << c.name;
  // Nothing is proven by two empty volumes, except where the grid misses the mesh on purpose.
  if (c.name != "grid_misses_mesh") {
    EXPECT_GT(cmp->intersection, 0) << c.name;
  }
}

TEST_P(Voxelize1DOracle, ThreadsAndRobustModeChangeNothing) {
  const Case& c = GetParam();
  VoxelizeOptions o;
  o.fill_rule = c.rule;
  auto one = voxelize_1d(c.mesh, c.grid, o);
  ASSERT_TRUE(one.ok());
  o.threads = 2;
  auto two = voxelize_1d(c.mesh, c.grid, o);
  ASSERT_TRUE(two.ok());
  EXPECT_EQ(one->volume.runs, two->volume.runs);
  EXPECT_EQ(one->volume.line_start, two->volume.line_start);
  // The three-axis vote perturbs each axis's lines its own way, so voxel centres lying exactly on
  // the surface may vote differently; everywhere else a closed mesh gives the same voxels.
  for (const char* exact : {"on_voxel_centres", "snapped", "on_centres", "lattice"}) {
    if (c.name.find(exact) != std::string::npos) return;
  }
  o.robust = true;
  auto robust = voxelize_1d(c.mesh, c.grid, o);
  ASSERT_TRUE(robust.ok());
  EXPECT_EQ(one->volume.runs, robust->volume.runs);
}

INSTANTIATE_TEST_SUITE_P(Shapes, Voxelize1DOracle, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

// A tetrahedron v0..v3 as an outward-oriented mesh.
TriangleMesh tetrahedron(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3) {
  TriangleMesh m;
  m.vertices_mm = {v0, v1, v2, v3};
  m.triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  orient_outward(m);
  return m;
}

// Ties that double arithmetic gets wrong. Each tetrahedron has an edge through the voxel centre
// q = (4,4,4) exactly (endpoints q + a d and q - b d with dyadic a, b, d), and a face whose plane
// also contains q. Evaluated in double, the edge function at q is a difference of two differently
// rounded products of the same exact value: often a tiny nonzero number of either sign, where the
// exact value is 0 and the tie rule must decide. Both methods must give the oracle's voxels.
TEST(Voxelize1DOracleTies, EdgesAndFacesExactlyThroughAVoxelCentre) {
  const ImageGeometry g = grid(9, 9, 9);
  const Vec3 q{4, 4, 4};
  std::mt19937_64 rng(5);
  auto dyadic = [&](int bits) {  // a multiple of 2^-30 in (-2^(bits-30), 2^(bits-30))
    return std::ldexp(double(std::uniform_int_distribution<int64_t>(-(int64_t(1) << bits), int64_t(1) << bits)(rng)),
                      -30);
  };
  int rounding_would_lie = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 d{dyadic(31), dyadic(31), dyadic(31)};
    const double a = 1 + std::abs(dyadic(29)), b = 1 + std::abs(dyadic(29));
    const Vec3 v0 = q + a * d, v1 = q - b * d;
    const Vec3 v2 = q + Vec3{dyadic(31), dyadic(31), dyadic(31)};
    const Vec3 v3 = q + Vec3{dyadic(31), dyadic(31), dyadic(31)};
    const TriangleMesh m = tetrahedron(v0, v1, v2, v3);
    if (mesh_defects(m).degenerate_triangles > 0) continue;
    // How plain double arithmetic would see the edge v0-v1 at (j, k) = (4, 4).
    const double naive = (v1[1] - v0[1]) * (q[2] - v0[2]) - (v1[2] - v0[2]) * (q[1] - v0[1]);
    rounding_would_lie += naive != 0;
    auto ours = voxelize_1d(m, g);
    ASSERT_TRUE(ours.ok()) << ours.status().to_string();
    auto oracle = voxelize_3d_raycast(m, g);
    ASSERT_TRUE(oracle.ok());
    auto cmp = compare(ours->volume, *oracle);
    ASSERT_TRUE(cmp.ok());
    ASSERT_EQ(cmp->only_a + cmp->only_b, 0) << "tetrahedron " << trial;
  }
  EXPECT_GT(rounding_would_lie, 30);  // the exact path was needed, not just taken
}

}  // namespace
}  // namespace soiq
