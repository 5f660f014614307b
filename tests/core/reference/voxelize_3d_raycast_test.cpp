#include "core/reference/voxelize_3d_raycast.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "core/geometry/primitives.h"
#include "core/reference/index_space_vertices.h"
#include "tests/core/reference/reference_test_support.h"

namespace soiq {
namespace {

using test::cube_grid;
using test::differing;

TEST(Voxelize3DRaycast, SphereMatchesAnalyticTestAwayFromTheSurface) {
  ImageGeometry g = cube_grid(24);
  g.origin_mm = {-6.1, -5.7, -6.3};
  g.spacing_mm = {0.55, 0.5, 0.6};
  const Vec3 c{0.3, -0.2, 0.4};
  const double r = 5.2;
  const TriangleMesh m = test::uv_sphere_mesh(c, r, 48, 96);
  const double s = test::sagitta(m, c, r);
  ASSERT_LT(s, 0.02);
  const auto v = voxelize_3d_raycast(m, g);
  ASSERT_TRUE(v.ok());
  const auto mask = to_mask(*v);
  int64_t checked = 0, wrong = 0;
  for (int64_t k = 0; k < 24; ++k)
    for (int64_t j = 0; j < 24; ++j)
      for (int64_t i = 0; i < 24; ++i) {
        const double d = norm(g.index_to_physical({double(i), double(j), double(k)}) - c);
        // Centres within the sagitta band (plus 1e-9 for rounding) may go either way.
        if (d > r - s - 1e-9 && d < r + 1e-9) continue;
        ++checked;
        wrong += mask->voxels[size_t(i + 24 * (j + 24 * k))] != (d < r);
      }
  EXPECT_GT(checked, 13000);
  EXPECT_EQ(wrong, 0);
}

TEST(Voxelize3DRaycast, InwardFacingSurfaceGivesTheSameVoxels) {
  const ImageGeometry g = cube_grid(8);
  TriangleMesh m = test::octahedron({3.2, 3.6, 2.9}, 2.7);
  const auto outward = voxelize_3d_raycast(m, g);
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  const auto inward = voxelize_3d_raycast(m, g);
  ASSERT_TRUE(outward.ok() && inward.ok());
  EXPECT_GT(voxel_count(*outward), 0);
  EXPECT_EQ(outward->runs, inward->runs);
  EXPECT_EQ(outward->line_start, inward->line_start);
}

// The voxels of the contract evaluated by brute force, every quantity an exact rational: every
// triangle against every line (no buckets), no floating-point filter, and the crossing x written
// out as a rational from barycentric weights (the oracle instead takes the sign of a 3x3
// determinant). Counts the ties it meets, so a test can show it probes them.
struct ExactVoxels {
  std::vector<uint8_t> inside;  // dense, i fastest
  int64_t ties = 0;             // an edge function or x - i exactly 0
  int64_t near_ties = 0;        // one within 1e-12 of 0, not 0: where long double could round wrong
};

int perturbed_sign(const mpq_class& e, const Vec3& a, const Vec3& b) {
  if (sgn(e) != 0) return sgn(e);
  if (b[2] != a[2]) return b[2] > a[2] ? -1 : 1;  // E + (b_y - a_y) e^2 - (b_z - a_z) e
  return (b[1] > a[1]) - (b[1] < a[1]);
}

ExactVoxels exact_voxels(const TriangleMesh& mesh, const ImageGeometry& g, FillRule rule) {
  const auto u = index_space_vertices(mesh, g);
  EXPECT_TRUE(u.ok());
  const int64_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
  const mpq_class near(1e-12);
  ExactVoxels out;
  out.inside.assign(size_t(g.voxel_count()), 0);
  auto count_tie = [&](const mpq_class& v) {
    if (sgn(v) == 0) {
      ++out.ties;
    } else if (abs(v) < near) {
      ++out.near_ties;
    }
  };
  for (int64_t k = 0; k < nz; ++k) {
    for (int64_t j = 0; j < ny; ++j) {
      const mpq_class py(j), pz(k);
      std::vector<std::pair<mpq_class, int>> crossings;  // (x, sign(n_x))
      for (const auto& t : mesh.triangles) {
        const Vec3 &a = (*u)[size_t(t[0])], &b = (*u)[size_t(t[1])], &c = (*u)[size_t(t[2])];
        // Outside the closed (y, z) bounding box the perturbed point cannot be inside (exact test).
        if (double(j) < std::min({a[1], b[1], c[1]}) || double(j) > std::max({a[1], b[1], c[1]}) ||
            double(k) < std::min({a[2], b[2], c[2]}) || double(k) > std::max({a[2], b[2], c[2]})) {
          continue;
        }
        // mpq_class, not auto: gmpxx returns expression templates that would refer to dead temporaries.
        auto edge = [&](const Vec3& p, const Vec3& q) -> mpq_class {
          return (mpq_class(q[1]) - p[1]) * (pz - p[2]) - (mpq_class(q[2]) - p[2]) * (py - p[1]);
        };
        const mpq_class ab = edge(a, b), bc = edge(b, c), ca = edge(c, a);
        count_tie(ab);
        count_tie(bc);
        count_tie(ca);
        const int s = perturbed_sign(ab, a, b);
        if (s == 0 || perturbed_sign(bc, b, c) != s || perturbed_sign(ca, c, a) != s) continue;
        // Weights of a, b, c are bc, ca, ab over their sum (twice the projected area, n_x).
        const mpq_class x =
            mpq_class(a[0]) + (ca * (mpq_class(b[0]) - a[0]) + ab * (mpq_class(c[0]) - a[0])) / (ab + bc + ca);
        crossings.emplace_back(x, s);
      }
      for (int64_t i = 0; i < nx; ++i) {
        int64_t winding = 0, count = 0;
        for (const auto& [x, s] : crossings) {
          const mpq_class ahead = x - i;
          count_tie(ahead);
          if (sgn(ahead) > 0) {
            winding += s;
            ++count;
          }
        }
        out.inside[size_t(i + nx * (j + ny * k))] = rule == FillRule::kNonZero ? winding != 0 : (count & 1) != 0;
      }
    }
  }
  return out;
}

struct TieCase {
  std::string name;
  TriangleMesh mesh;
  ImageGeometry grid;
  FillRule rule = FillRule::kNonZero;
};

void PrintTo(const TieCase& c, std::ostream* os) { *os << c.name; }

// Coarse meshes centred on voxel centres (core/geometry/primitives, whose exact vertex bits make the ties):
// many lines run through vertices and edges, and several centres lie within 1e-15 of a face,
// where a floating-point evaluation (even long double) can decide either way.
std::vector<TieCase> tie_cases() {
  std::vector<TieCase> cs;
  cs.push_back({"lattice_centred_sphere", uv_sphere({8, 8, 8}, 6, 4, 8), cube_grid(17)});
  cs.push_back({"lattice_centred_sphere_even_odd", uv_sphere({8, 8, 8}, 6, 4, 8), cube_grid(17), FillRule::kEvenOdd});
  cs.push_back({"sphere_vertices_on_centres", uv_sphere({10, 10, 10}, 7, 8, 16), cube_grid(21)});
  cs.push_back({"lattice_centred_torus", torus({8, 8, 8}, 5, 2, 16, 8), cube_grid(17)});
  ImageGeometry half = cube_grid(33);
  half.spacing_mm = {0.5, 0.5, 0.5};
  cs.push_back({"lattice_centred_sphere_half_spacing", uv_sphere({8, 8, 8}, 6, 6, 12), half});
  // Vertices on the lattice (integers, or half-integers for the voxel faces): the oracle's
  // exact-in-double shortcut for lattice inputs decides every tie here.
  cs.push_back({"lattice_octahedron", test::octahedron({8, 8, 8}, 5), cube_grid(17)});
  cs.push_back({"lattice_box_unit_facets", test::tessellated_box({2, 3, 1}, {12, 9, 14}, 2), cube_grid(17)});
  Mask blob;
  blob.geometry = cube_grid(9);
  blob.voxels.resize(size_t(blob.geometry.voxel_count()));
  std::mt19937 rng(3);
  for (auto& v : blob.voxels) v = (rng() % 2) == 0;
  cs.push_back({"voxel_faces_on_half_integers", test::cuberille(blob), cube_grid(9)});
  return cs;
}

class Voxelize3DRaycastTies : public ::testing::TestWithParam<TieCase> {};

TEST_P(Voxelize3DRaycastTies, EqualsAnAllRationalEvaluation) {
  const TieCase& c = GetParam();
  const ExactVoxels exact = exact_voxels(c.mesh, c.grid, c.rule);
  // The case must still probe what it is for: ties and near-ties.
  ASSERT_GT(exact.ties, 0) << c.name;
  const auto r = voxelize_3d_raycast(c.mesh, c.grid, c.rule);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_GT(voxel_count(*r), 0);
  EXPECT_EQ(differing(*r, exact.inside), 0) << c.name << ": " << exact.near_ties << " near-ties";
}

INSTANTIATE_TEST_SUITE_P(LatticeMeshes, Voxelize3DRaycastTies, ::testing::ValuesIn(tie_cases()),
                         [](const auto& info) { return info.param.name; });

// The lattice-centred sphere has centres within 1e-12 (in fact 1e-15) of a face that are not on
// it: a case that separates exact predicates from long double ones.
TEST(Voxelize3DRaycast, LatticeCentredSphereHasNearTies) {
  EXPECT_GT(exact_voxels(uv_sphere({8, 8, 8}, 6, 4, 8), cube_grid(17), FillRule::kNonZero).near_ties, 0);
}

// Tetrahedra with one face through the centre q = (4, 4, 4) exactly, at barycentric weights
// (1/4, 1/4, 1/2): v0 + v1 + 2 v2 = 4q with all coordinates multiples of 2^-40, so the tie is exact
// in the doubles. The face's (y, z) projection is a needle (length ~2, width ~1e-4 along y = z),
// so its edge functions at q cancel ~1e4-fold and a floating-point crossing x lands within ~1e-15
// of 4 on either side: long double rounds it. Half-open rule: q is inside iff that face is
// entering (outward n_x < 0).
TEST(Voxelize3DRaycast, CentreExactlyOnANeedleFaceFollowsTheHalfOpenRule) {
  const ImageGeometry g = cube_grid(9);
  const Vec3 q{4, 4, 4};
  std::mt19937_64 rng(11);
  auto dyadic = [&](int bits) {  // a multiple of 2^-40 in (-2^(bits-40), 2^(bits-40))
    return std::ldexp(double(std::uniform_int_distribution<int64_t>(-(int64_t(1) << bits), int64_t(1) << bits)(rng)),
                      -40);
  };
  int tested = 0, inside = 0;
  while (tested < 200) {
    const double s0 = dyadic(40), s2 = dyadic(40);
    const Vec3 d0{dyadic(40), s0, s0 + dyadic(27)}, d2{dyadic(40), s2, s2 + dyadic(27)};
    const Vec3 v0 = q + d0, v2 = q + d2, v1 = q - d0 - 2.0 * d2;
    const Vec3 n = cross(v1 - v0, v2 - v0);
    // Keep n_x clear of zero so that its sign, in double, is certain.
    if (std::abs(n[0]) < 1e-7 * norm(n)) continue;
    const Vec3 v3 = q + (tested % 2 ? 1.5 : -1.5) * (1 / norm(n)) * n + Vec3{0.3, -0.2, 0.1};
    test::MeshBuilder b;
    b.triangle(v0, v1, v2, v0 - v3);
    b.triangle(v0, v1, v3, v0 - v2);
    b.triangle(v1, v2, v3, v1 - v0);
    b.triangle(v2, v0, v3, v2 - v1);
    const Vec3 outward = dot(n, v0 - v3) > 0 ? n : -1.0 * n;
    const auto r = voxelize_3d_raycast(b.mesh(), g);
    ASSERT_TRUE(r.ok());
    const auto mask = to_mask(*r);
    ASSERT_TRUE(mask.ok());
    EXPECT_EQ(mask->voxels[size_t(4 + 9 * (4 + 9 * 4))], outward[0] < 0) << "tetrahedron " << tested;
    EXPECT_EQ(differing(*r, exact_voxels(b.mesh(), g, FillRule::kNonZero).inside), 0) << "tetrahedron " << tested;
    inside += outward[0] < 0;
    ++tested;
  }
  EXPECT_GT(inside, 50);  // both sides of the rule are exercised
  EXPECT_LT(inside, 150);
}

TEST(Voxelize3DRaycast, VertexIndexOutOfRangeIsInvalidArgument) {
  TriangleMesh m = test::octahedron({3, 3, 3}, 2);
  m.triangles[2][1] = 99;
  const auto r = voxelize_3d_raycast(m, cube_grid(4));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("vertex 99"), std::string::npos);
}

TEST(Voxelize3DRaycast, BadSpacingIsInvalidArgument) {
  ImageGeometry g = cube_grid(4);
  g.spacing_mm[1] = 0;
  const auto r = voxelize_3d_raycast(test::octahedron({3, 3, 3}, 2), g);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("spacing"), std::string::npos);
}

}  // namespace
}  // namespace soiq
