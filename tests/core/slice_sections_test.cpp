// Sections of closed surfaces by a grid's slice planes (core/geometry/slice_sections.h), judged by
// the 1D method: the sections filled by fill_contours (even-odd) must give exactly the voxels
// voxelize_1d gives the surface (even-odd), on shapes with vertices, edges and faces lying in the
// planes, holes, several parts, and oblique grids.
#include "core/geometry/slice_sections.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/geometry/primitives.h"
#include "core/io/marching_cubes.h"
#include "core/voxelize/fill_contours.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

ImageGeometry axis_grid(int64_t n, double spacing) {
  ImageGeometry g;
  g.dims = {n, n, n};
  g.spacing_mm = {spacing, spacing, spacing};
  return g;
}

// A grid turned 30 degrees about z and 20 about x, with uneven spacing: no plane is aligned with
// the shapes' faces.
ImageGeometry oblique_grid() {
  ImageGeometry g;
  g.dims = {40, 36, 30};
  g.spacing_mm = {0.7, 0.8, 1.3};
  g.origin_mm = {-3.1, -2.2, -4.7};
  const double a = 0.5235987755982988, b = 0.3490658503988659;
  const Mat3 rz = {{{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}}};
  const Mat3 rx = {{{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) g.direction[r][c] = dot(rz[r], {rx[0][c], rx[1][c], rx[2][c]});
  return g;
}

// A blob of voxels on `g` (two overlapping balls and a bar, so that its surface has concave parts,
// a cavity and faces in the slice planes) as marching cubes makes it: the kind of surface soiq
// stores for an imported structure, every vertex on a grid edge.
TriangleMesh marching_cubes_blob(const ImageGeometry& g) {
  Mask m{g, std::vector<uint8_t>(size_t(g.voxel_count()), 0)};
  for (int64_t k = 0; k < g.dims[2]; ++k)
    for (int64_t j = 0; j < g.dims[1]; ++j)
      for (int64_t i = 0; i < g.dims[0]; ++i) {
        auto d2 = [&](double x, double y, double z) {
          return (i - x) * (i - x) + (j - y) * (j - y) + (k - z) * (k - z);
        };
        const bool ball = d2(8, 8, 8) < 30 || d2(12, 10, 9) < 20;
        const bool cavity = d2(8, 8, 8) < 4;
        const bool bar = i >= 3 && i <= 16 && j == 15 && k >= 4 && k <= 6;
        m.voxels[size_t(i + g.dims[0] * (j + g.dims[1] * k))] = uint8_t((ball && !cavity) || bar);
      }
  auto mesh = marching_cubes(m);
  EXPECT_TRUE(mesh.ok()) << mesh.status().to_string();
  return mesh.ok() ? *mesh : TriangleMesh{};
}

struct Case {
  std::string name;
  TriangleMesh mesh;
  ImageGeometry grid;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::vector<Case> cases() {
  const ImageGeometry unit = axis_grid(20, 1.0);
  const ImageGeometry half = axis_grid(40, 0.5);
  // A box whose faces lie in planes and pass through voxel centres, with a box-shaped cavity.
  const TriangleMesh hollow = merge(box({2, 2, 2}, {12, 12, 9}), flipped(box({5, 4, 4}, {9, 8, 7})));
  const TriangleMesh two_parts = merge(uv_sphere({6, 6, 7}, 4, 12, 16), uv_sphere({14, 13, 11}, 3.5, 10, 14));
  const TriangleMesh ring = torus({10, 10, 9.5}, 5, 2.2, 24, 12);
  return {{"hollow_box_unit", hollow, unit},
          {"hollow_box_half", hollow, half},
          {"two_spheres_unit", two_parts, unit},
          {"torus_unit", ring, unit},
          {"torus_half", ring, half},
          {"torus_oblique", ring, oblique_grid()},
          {"two_spheres_oblique", two_parts, oblique_grid()},
          {"marching_cubes_blob", marching_cubes_blob(unit), unit}};
}

class SliceSectionsFill : public ::testing::TestWithParam<Case> {};

TEST_P(SliceSectionsFill, FilledEvenOddGiveTheVoxelsOfThe1DMethod) {
  const Case& c = GetParam();
  auto sections = slice_sections(c.mesh, c.grid, c.name);
  ASSERT_TRUE(sections.ok()) << sections.status().to_string();
  std::vector<PlanarContour> contours;
  for (const SliceSection& s : *sections) contours.push_back({s.points_mm});
  auto filled = fill_contours(contours, c.grid, FillRule::kEvenOdd, 1e-6);
  ASSERT_TRUE(filled.ok()) << filled.status().to_string();
  VoxelizeOptions o;
  o.fill_rule = FillRule::kEvenOdd;
  auto voxels = voxelize_1d(c.mesh, c.grid, o);
  ASSERT_TRUE(voxels.ok()) << voxels.status().to_string();
  auto cmp = compare(filled->volume, voxels->volume);
  ASSERT_TRUE(cmp.ok()) << cmp.status().to_string();
  EXPECT_GT(cmp->count_b, 0);
  EXPECT_EQ(cmp->only_a, 0) << "voxels inside the sections but not the surface";
  EXPECT_EQ(cmp->only_b, 0) << "voxels inside the surface but not the sections";
}

INSTANTIATE_TEST_SUITE_P(Shapes, SliceSectionsFill, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

// Twice the signed area of a section in index space (x, y): positive counter-clockwise.
double signed_area2(const SliceSection& s, const ImageGeometry& g) {
  double a = 0;
  for (size_t i = 0; i < s.points_mm.size(); ++i) {
    const Vec3 p = g.physical_to_index(s.points_mm[i]);
    const Vec3 q = g.physical_to_index(s.points_mm[(i + 1) % s.points_mm.size()]);
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a;
}

TEST(SliceSections, HoleIsASeparateClockwiseContour) {
  const ImageGeometry g = axis_grid(20, 1.0);
  const TriangleMesh hollow = merge(box({2, 2, 2}, {12, 12, 9}), flipped(box({5, 4, 4}, {9, 8, 7})));
  auto sections = slice_sections(hollow, g);
  ASSERT_TRUE(sections.ok()) << sections.status().to_string();
  // Planes 2..8 cut the outer box (plane 9 holds its top face: not cut, the d -> 0+ rule); planes
  // 4..6 also cut the cavity.
  int outer = 0, holes = 0;
  for (const SliceSection& s : *sections) {
    const double a2 = signed_area2(s, g);
    if (a2 > 0) {
      ++outer;
      EXPECT_DOUBLE_EQ(a2, 2 * 10 * 10) << "slice " << s.slice;
    } else {
      ++holes;
      EXPECT_DOUBLE_EQ(a2, -2 * 4 * 4) << "slice " << s.slice;
      EXPECT_GE(s.slice, 4);
      EXPECT_LE(s.slice, 6);
    }
  }
  EXPECT_EQ(outer, 7);
  EXPECT_EQ(holes, 3);
}

TEST(SliceSections, TwoPartsAreTwoContoursOnOnePlane) {
  const ImageGeometry g = axis_grid(20, 1.0);
  auto sections = slice_sections(merge(box({1, 1, 1}, {5, 5, 5}), box({8, 1, 2}, {12, 6, 4})), g);
  ASSERT_TRUE(sections.ok()) << sections.status().to_string();
  int on_plane_3 = 0;
  for (const SliceSection& s : *sections) on_plane_3 += s.slice == 3;
  EXPECT_EQ(on_plane_3, 2);
}

TEST(SliceSections, SurfaceTouchingAPlaneAtOneVertexGivesNoContour) {
  // An octahedron whose top vertex lies in plane 6: that plane's section is a point, left out.
  TriangleMesh m;
  m.vertices_mm = {{5, 5, 2}, {5, 5, 6}, {3, 5, 4}, {7, 5, 4}, {5, 3, 4}, {5, 7, 4}};
  m.triangles = {{0, 3, 4}, {0, 5, 3}, {0, 2, 5}, {0, 4, 2}, {1, 4, 3}, {1, 3, 5}, {1, 5, 2}, {1, 2, 4}};
  auto sections = slice_sections(m, axis_grid(10, 1.0));
  ASSERT_TRUE(sections.ok()) << sections.status().to_string();
  ASSERT_FALSE(sections->empty());
  for (const SliceSection& s : *sections) {
    EXPECT_GE(s.slice, 2);  // plane 2 holds the bottom vertex and is cut (into a point: left out)
    EXPECT_LE(s.slice, 5);
    EXPECT_GE(s.points_mm.size(), 3u);
  }
}

TEST(SliceSections, OpenSurfaceIsRefusedNamingIt) {
  TriangleMesh m = box({1, 1, 1}, {5, 5, 5});
  m.triangles.pop_back();
  auto sections = slice_sections(m, axis_grid(10, 1.0), "GTV");
  ASSERT_FALSE(sections.ok());
  EXPECT_EQ(sections.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(sections.status().message().find("'GTV' is not closed"), std::string::npos) << sections.status().message();
}

TEST(SliceSections, EmptyMeshIsInvalid) {
  auto sections = slice_sections(TriangleMesh{}, axis_grid(10, 1.0));
  ASSERT_FALSE(sections.ok());
  EXPECT_EQ(sections.status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
