// Unevenly spaced grids (slices where the series has them, never resampled): the 1D method slice
// by slice against VTK's vtkPolyDataToImageStencil on a one-slice grid through that slice alone
// (mapped by this test's own Cramer's rule), the sections of a surface filled back, the nearest
// plane rule between unequal gaps, the volume features against sums over every voxel centre, the
// mask's surface features against VTK's marching cubes in mm, and what such a grid refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/features/marching_cubes_table.h"
#include "core/features/mask_surface_mesh.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/features/structure_features.h"
#include "core/features/surface_shape.h"
#include "core/features/volume_shape.h"
#include "core/geometry/primitives.h"
#include "core/geometry/slice_sections.h"
#include "core/io/marching_cubes.h"
#include "core/io/write_image.h"
#include "core/regions/regions.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/fill_contours.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/core/vtk_stencil_oracle.h"

namespace soiq {
namespace {

Vec3 unit(const Vec3& v) { return (1 / norm(v)) * v; }

// A stack as a scanner writes it: rows and columns, pixel spacing, and each slice's first pixel.
struct Stack {
  std::string name;
  Vec3 row, col;
  double sx, sy;
  int64_t nx, ny;
  std::vector<Vec3> firsts;

  ImageGeometry geometry() const {
    ImageGeometry g;
    g.origin_mm = firsts.front();
    g.dims = {nx, ny, int64_t(firsts.size())};
    const Vec3 span = firsts.back() - firsts.front();
    const Vec3 k = unit(span);
    const Vec3 n = cross(row, col);
    for (const Vec3& f : firsts) g.slice_positions_mm.push_back(dot(f - firsts.front(), n) / dot(k, n));
    g.slice_positions_mm[0] = 0;
    g.spacing_mm = {sx, sy, g.slice_positions_mm.back() / double(firsts.size() - 1)};
    for (int r = 0; r < 3; ++r) g.direction[size_t(r)] = {row[size_t(r)], col[size_t(r)], k[size_t(r)]};
    return g;
  }
};

// p -> (i, j, h) in the grid of slice k alone: axes sx row, sy col and the unit normal, origin
// slice k's first pixel (Cramer's rule), so the slice is the plane h = 0.
Vec3 to_slice_index(const Stack& s, size_t k, const Vec3& p) {
  const Vec3 n = cross(s.row, s.col);
  Mat3 a{};
  for (size_t r = 0; r < 3; ++r) a[r] = {s.sx * s.row[r], s.sy * s.col[r], n[r]};
  return testing::cramer_solve(a, p - s.firsts[k]);
}

// VTK's stencil of the mesh on slice k alone: the mesh mapped into that slice's grid and cut by
// its plane h = 0.
std::vector<uint8_t> vtk_slice(const TriangleMesh& mesh, const Stack& s, size_t k) {
  return testing::vtk_stencil(mesh, [&](const Vec3& p) { return to_slice_index(s, k, p); }, {s.nx, s.ny, 1});
}

// A CT protocol finer through the middle (axial), and the same irregular steps on an oblique,
// tilted stack.
std::vector<Stack> stacks() {
  const double z[] = {-16, -11, -7.5, -5, -3.75, -2.5, -1.25, 0, 1.25, 2.5, 3.75, 5, 8, 12, 17.5};
  Stack axial{"axial, 1.25 to 5.5 mm", {1, 0, 0}, {0, 1, 0}, 0.8, 0.8, 50, 48, {}};
  for (const double h : z) axial.firsts.push_back({-19.6, -18.8, h});
  const Vec3 row = unit({0.8, 0.6, 0.0}), col = unit(cross({0.3, -0.4, 0.866}, row));
  const Vec3 n = cross(row, col), lean = 0.3 * row - 0.2 * col;  // in-plane shift per mm of height
  Stack oblique{"oblique, tilted, 1.25 to 5.5 mm", row, col, 0.7, 0.9, 58, 48, {}};
  const Vec3 corner = -20.0 * row + (-21.0) * col;
  for (const double h : z) oblique.firsts.push_back(corner + h * n + h * lean);
  return {axial, oblique};
}

std::vector<std::pair<std::string, TriangleMesh>> shapes() {
  const Mat3 r = rotation_about(unit({1, 2, 3}), 0.7);
  return {{"ellipsoid", transformed(uv_sphere({0, 0, 0}, 1, 40, 60), {12, 8, 10}, r, {0.3, -0.2, 0.4})},
          {"torus", transformed(torus({0, 0, 0}, 8, 3.5, 64, 24), {1, 1, 1}, r, {-0.5, 0.6, 0.1})}};
}

TEST(UnevenGrid, OneDMethodEqualsVtkStencilOnEverySlice) {
  for (const Stack& s : stacks()) {
    const ImageGeometry g = s.geometry();
    ASSERT_TRUE(validate_geometry(g).ok()) << validate_geometry(g).to_string();
    ASSERT_TRUE(g.uneven());
    for (size_t k = 0; k < s.firsts.size(); ++k) {
      const Vec3 p = g.index_to_physical({2, 3, double(k)});
      const Vec3 want = s.firsts[k] + (2 * s.sx) * s.row + (3 * s.sy) * s.col;
      for (int a = 0; a < 3; ++a) ASSERT_NEAR(p[size_t(a)], want[size_t(a)], 1e-12) << s.name << " slice " << k;
    }
    for (const auto& [shape, mesh] : shapes()) {
      auto v = voxelize_1d(mesh, g);
      ASSERT_TRUE(v.ok()) << v.status().to_string();
      auto ours = to_mask(v->volume);
      ASSERT_TRUE(ours.ok());
      int64_t differ = 0, inside = 0;
      for (size_t k = 0; k < s.firsts.size(); ++k) {
        const std::vector<uint8_t> vtk = vtk_slice(mesh, s, k);
        for (size_t n = 0; n < vtk.size(); ++n) {
          differ += ours->voxels[k * vtk.size() + n] != vtk[n];
          inside += vtk[n];
        }
      }
      std::cout << s.name << ", " << shape << ": " << inside << " voxels inside (VTK, slice by slice), " << differ
                << " differing\n";
      EXPECT_GT(inside, 1000) << s.name << ", " << shape;
      EXPECT_EQ(differ, 0) << s.name << ", " << shape;

      // The surface's sections by the slices, filled by the contour filler: the same voxels.
      auto sections = slice_sections(mesh, g, shape);
      ASSERT_TRUE(sections.ok()) << sections.status().to_string();
      std::vector<PlanarContour> contours;
      for (const SliceSection& c : *sections) contours.push_back({c.points_mm});
      auto filled = fill_contours(contours, g);
      ASSERT_TRUE(filled.ok()) << filled.status().to_string();
      auto cmp = compare(filled->volume, v->volume);
      ASSERT_TRUE(cmp.ok());
      EXPECT_EQ(cmp->only_a + cmp->only_b, 0) << s.name << ", " << shape << ": sections filled back";
    }
  }
}

TEST(UnevenGrid, ContourGoesToTheNearestPlaneWithinItsOwnGapOrIsRefused) {
  ImageGeometry g;
  g.dims = {10, 10, 3};
  g.slice_positions_mm = {0, 2, 7};
  g.spacing_mm = {1, 1, 3.5};
  auto square = [](double z) { return PlanarContour{{{2.2, 2.2, z}, {6.8, 2.2, z}, {6.8, 6.8, z}, {2.2, 6.8, z}}}; };
  for (const auto& [z, slice] : std::vector<std::pair<double, int>>{{0.8, 0}, {1.2, 1}, {3.9, 1}, {5.0, 2}}) {
    auto f = fill_contours({square(z)}, g);
    ASSERT_TRUE(f.ok()) << z << ": " << f.status().to_string();
    auto mask = to_mask(f->volume);
    ASSERT_TRUE(mask.ok());
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mask->voxels[size_t(k * 100 + 44)], k == slice) << "contour at " << z;
  }
  // 2.4 mm above plane 1, in a 5 mm gap: more than 0.45 of it.
  auto refused = fill_contours({square(4.4)}, g);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("lies 2.4 mm from the nearest image plane (slice 1), more than 2.25 mm"),
            std::string::npos)
      << refused.status().message();
}

TEST(UnevenGrid, VolumeFeaturesWeighEachSlicesVoxels) {
  const Stack s = stacks()[1];
  const ImageGeometry g = s.geometry();
  auto v = voxelize_1d(shapes()[0].second, g);
  ASSERT_TRUE(v.ok());
  auto shape = volume_shape(v->volume);
  ASSERT_TRUE(shape.ok()) << shape.status().to_string();
  auto mask = to_mask(v->volume);
  ASSERT_TRUE(mask.ok());
  // Every voxel centre from the stack itself.
  double volume = 0, n = 0;
  Vec3 sum{0, 0, 0};
  std::vector<Vec3> centres;
  const Vec3 normal = cross(s.row, s.col);
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    const double below =
        k > 0 ? dot(s.firsts[size_t(k)] - s.firsts[size_t(k - 1)], normal) : dot(s.firsts[1] - s.firsts[0], normal);
    const double above = k + 1 < g.dims[2] ? dot(s.firsts[size_t(k + 1)] - s.firsts[size_t(k)], normal)
                                           : dot(s.firsts[size_t(k)] - s.firsts[size_t(k - 1)], normal);
    for (int64_t j = 0; j < g.dims[1]; ++j)
      for (int64_t i = 0; i < g.dims[0]; ++i) {
        if (!mask->voxels[size_t(i + g.dims[0] * (j + g.dims[1] * k))]) continue;
        const Vec3 p = s.firsts[size_t(k)] + (double(i) * s.sx) * s.row + (double(j) * s.sy) * s.col;
        centres.push_back(p);
        sum = sum + p;
        n += 1;
        volume += s.sx * s.sy * 0.5 * (below + above);
      }
  }
  const Vec3 centroid = (1 / n) * sum;
  EXPECT_NEAR(shape->voxel_volume_mm3, volume, 1e-9 * volume);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(shape->centroid_mm[size_t(a)], centroid[size_t(a)], 1e-9);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double c = 0;
      for (const Vec3& p : centres) c += (p[size_t(a)] - centroid[size_t(a)]) * (p[size_t(b)] - centroid[size_t(b)]);
      EXPECT_NEAR(shape->covariance_mm2[size_t(a)][size_t(b)], c / n, 1e-7) << a << "," << b;
    }
}

TEST(UnevenGrid, MaskSurfaceFeaturesAreThoseOfVtksMarchingCubesInMm) {
  for (const Stack& s : stacks()) {
    for (const auto& [name, mesh] : shapes()) {
      const ImageGeometry g = s.geometry();
      auto v = voxelize_1d(mesh, g);
      ASSERT_TRUE(v.ok());
      auto ours = mask_surface_mesh(v->volume, marching_cubes_table());
      ASSERT_TRUE(ours.ok()) << ours.status().to_string();
      auto mask = to_mask(v->volume);
      ASSERT_TRUE(mask.ok());
      auto vtk = marching_cubes(*mask);
      ASSERT_TRUE(vtk.ok()) << vtk.status().to_string();
      auto a = surface_shape(*ours, g.frame()), b = surface_shape(*vtk, g.frame());
      ASSERT_TRUE(a.ok() && b.ok());
      const std::string what = s.name + ", " + name;
      EXPECT_EQ(ours->triangles.size(), vtk->triangles.size()) << what;
      EXPECT_NEAR(a->mesh_volume_mm3, b->mesh_volume_mm3, 1e-9 * b->mesh_volume_mm3) << what;
      EXPECT_NEAR(a->surface_area_mm2, b->surface_area_mm2, 1e-9 * b->surface_area_mm2) << what;
      EXPECT_NEAR(a->maximum_3d_diameter_mm, b->maximum_3d_diameter_mm, 1e-9) << what;
      EXPECT_NEAR(a->convex_hull_volume_mm3, b->convex_hull_volume_mm3, 1e-9 * b->convex_hull_volume_mm3) << what;
      // The features engine takes that road on such a grid: its mask features are these.
      FeatureRequest request;
      request.names = {"mesh_volume_mm3", "surface_area_mm2", "maximum_2d_diameter_row_mm",
                       "maximum_2d_diameter_slice_mm", "voxel_volume_mm3"};
      auto report = structure_features({v->volume, nullptr}, request);
      ASSERT_TRUE(report.ok()) << report.status().to_string();
      auto d = maximum_2d_diameters(*vtk, g);
      ASSERT_TRUE(d.ok());
      for (const Feature& f : report->features) {
        double want = f.value[0];
        if (f.name == "mesh_volume_mm3") want = b->mesh_volume_mm3;
        if (f.name == "surface_area_mm2") want = b->surface_area_mm2;
        if (f.name == "maximum_2d_diameter_row_mm") want = d->row_mm;
        if (f.name == "maximum_2d_diameter_slice_mm") want = d->slice_mm;
        EXPECT_NEAR(f.value[0], want, 1e-9 * std::max(1.0, want)) << what << " " << f.name;
      }
      EXPECT_EQ(report->features.size(), request.names.size()) << what;
    }
  }
}

// A plane of constant i holds the leaning, unevenly spaced k axis: its diameter, measured in mm
// over every pair of the surface's vertices on that plane, equals the feature's.
TEST(UnevenGrid, TwoDDiametersAreDistancesInMmWithinEachPlane) {
  const Stack s = stacks()[1];
  const ImageGeometry g = s.geometry();
  auto v = voxelize_1d(shapes()[1].second, g);
  ASSERT_TRUE(v.ok());
  auto mask = to_mask(v->volume);
  ASSERT_TRUE(mask.ok());
  auto mesh = marching_cubes(*mask);
  ASSERT_TRUE(mesh.ok());
  auto d = maximum_2d_diameters(*mesh, g);
  ASSERT_TRUE(d.ok());
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<std::pair<int64_t, Vec3>> points;
    for (const Vec3& p : mesh->vertices_mm)
      points.push_back({std::llround(2 * g.physical_to_index(p)[size_t(axis)]), p});
    std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    double best = 0;
    for (size_t a = 0; a < points.size();) {
      size_t e = a;
      while (e < points.size() && points[e].first == points[a].first) ++e;
      for (size_t p = a; p < e; ++p)
        for (size_t q = p + 1; q < e; ++q) best = std::max(best, norm(points[p].second - points[q].second));
      a = e;
    }
    const double got = axis == 0 ? d->row_mm : axis == 1 ? d->column_mm : d->slice_mm;
    EXPECT_NEAR(got, best, 1e-9) << "axis " << axis;
  }
}

TEST(UnevenGrid, WhatNeedsEvenSlicesIsRefusedSayingWhatToDoInstead) {
  const ImageGeometry g = stacks()[0].geometry();
  const TriangleMesh mesh = shapes()[0].second;
  auto coverage = coverage_1d(mesh, g, CoverageOptions{});
  ASSERT_FALSE(coverage.ok());
  EXPECT_EQ(coverage.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(coverage.status().message().find("coverage fractions is not available on an unevenly spaced series"),
            std::string::npos)
      << coverage.status().message();
  VoxelizeOptions robust;
  robust.robust = true;
  auto voted = voxelize_1d(mesh, g, robust);
  ASSERT_FALSE(voted.ok());
  EXPECT_EQ(voted.status().code(), StatusCode::kFailedPrecondition);
  auto v = voxelize_1d(mesh, g);
  ASSERT_TRUE(v.ok());
  auto shell = region(v->volume, RegionSpec{RegionKind::kShell, 2});
  ASSERT_FALSE(shell.ok());
  EXPECT_EQ(shell.status().code(), StatusCode::kFailedPrecondition);
  auto mask = to_mask(v->volume);
  ASSERT_TRUE(mask.ok());
  const Status nifti = write_mask(*mask, "/nonexistent-dir/never-written.nii.gz");
  EXPECT_EQ(nifti.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(nifti.message().find("NIfTI, NRRD and MetaImage hold evenly spaced slices only"), std::string::npos)
      << nifti.message();
}

}  // namespace
}  // namespace soiq
