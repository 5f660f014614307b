// Shape features of finely meshed spheres and ellipsoids against their analytic values, within
// error bounds derived here; and invariance of every feature under a rigid motion of mesh and grid.
//
// Mesh error. uv_sphere's vertices lie on the sphere and its quads are planar, so the mesh is a
// convex polytope P inscribed in the ball B. With d = the smallest distance from the centre to a
// facet plane and eps = 1 - d / r, P contains (1 - eps) B. Nested convex bodies have nested volumes
// and areas, so V in [V0 (1-eps)^3, V0], A in [A0 (1-eps)^2, A0], sphericity in [(1-eps)^2, 1]
// (times the ellipsoid's own sphericity psi0, over [(1-eps)^2, (1-eps)^-2], for an ellipsoid: the
// unit-sphere mesh scaled per axis keeps all of this). Second moments about the centre scale as
// length^5 and volume as length^3, so a variance lies in [s0 (1-eps)^5, s0 (1-eps)^-3].
//
// Voxel error (axis lengths from voxel centres on a grid of spacing h). Two parts:
//  - the sum over centres is the integral over the voxel cells minus h^2/12 per variance
//    (midpoint rule for x^2 on each cell: exact);
//  - the cells' union differs from the body in a layer along the surface; the resulting relative
//    error of a moment is the lattice-point discrepancy of a smooth convex body of inradius
//    t = c / h voxels, O(t^(-3/2)) (Landau's bound for the ellipsoid problem in 3D); we take the
//    constant as 1. This part is an estimate, not a bound; the measured error is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "core/features/centre_of_mass_shift.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/features/surface_shape.h"
#include "core/features/volume_shape.h"
#include "core/geometry/primitives.h"
#include "core/io/marching_cubes.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

constexpr double kPi = std::numbers::pi;

// eps = 1 - (smallest facet-plane distance from the centre) / radius, for a mesh of the unit
// sphere about the origin.
double inscribed_gap(const TriangleMesh& unit) {
  double d = 1;
  for (const auto& t : unit.triangles) {
    const Vec3 &a = unit.vertices_mm[t[0]], &b = unit.vertices_mm[t[1]], &c = unit.vertices_mm[t[2]];
    const Vec3 n = cross(b - a, c - a);
    const double len = norm(n);
    if (len > 0) d = std::min(d, std::fabs(dot(n, a)) / len);
  }
  return 1 - d;
}

TriangleMesh scaled(TriangleMesh m, const Vec3& s, const Vec3& centre = {0, 0, 0}) {
  for (auto& v : m.vertices_mm) v = centre + Vec3{v[0] * s[0], v[1] * s[1], v[2] * s[2]};
  return m;
}

// Surface area of the ellipsoid with semi-axes a >= b >= c (Legendre's form).
double ellipsoid_area(double a, double b, double c) {
  const double phi = std::acos(c / a);
  const double k = std::sqrt(a * a * (b * b - c * c) / (b * b * (a * a - c * c)));
  const double s = std::sin(phi), co = std::cos(phi);
  return 2 * kPi * c * c + 2 * kPi * a * b / s * (std::ellint_2(k, phi) * s * s + std::ellint_1(k, phi) * co * co);
}

ImageGeometry grid_over(const Vec3& half_extent_mm, double h, const Vec3& centre) {
  ImageGeometry g;
  g.spacing_mm = {h, h, h};
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = int64_t(std::ceil(2 * half_extent_mm[a] / h)) + 3;
    // Offset the lattice by an irrational-looking fraction so no centre sits on a symmetry plane.
    g.origin_mm[a] = centre[a] - half_extent_mm[a] - h * 1.3183;
  }
  return g;
}

VolumeShape voxel_shape(const TriangleMesh& mesh, const ImageGeometry& g) {
  VoxelizeOptions o;
  o.threads = 2;
  const auto vox = voxelize_1d(mesh, g, o);
  EXPECT_TRUE(vox.ok()) << vox.status().to_string();
  if (!vox.ok()) return {};
  const auto s = volume_shape(vox->volume);
  EXPECT_TRUE(s.ok()) << s.status().to_string();
  return s.ok() ? *s : VolumeShape{};
}

// Relative tolerance of a variance s0 = (semi-axis)^2 / 5 sampled on spacing h, for a body of
// smallest semi-axis c and mesh gap eps (see the top of the file).
double variance_tolerance(double semi_axis, double c, double h, double eps) {
  const double mesh = std::max(1 - std::pow(1 - eps, 5), std::pow(1 - eps, -3) - 1);
  const double midpoint = h * h / 12 / (semi_axis * semi_axis / 5);
  const double lattice = std::pow(c / h, -1.5);
  return mesh + midpoint + lattice;
}

TEST(ShapeAnalytic, SphereOfRadius20) {
  const double r = 20;
  const TriangleMesh unit = uv_sphere({0, 0, 0}, 1, 200, 400);
  const double eps = inscribed_gap(unit);  // ~3.1e-5
  const Vec3 centre{3.2, -7.1, 40.6};
  const TriangleMesh mesh = scaled(unit, {r, r, r}, centre);
  const auto s = surface_shape(mesh);
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  const double v0 = 4 * kPi * r * r * r / 3, a0 = 4 * kPi * r * r;
  EXPECT_LE(s->mesh_volume_mm3, v0);
  EXPECT_GE(s->mesh_volume_mm3, v0 * std::pow(1 - eps, 3));
  EXPECT_LE(s->surface_area_mm2, a0);
  EXPECT_GE(s->surface_area_mm2, a0 * std::pow(1 - eps, 2));
  EXPECT_LE(s->sphericity, 1);
  EXPECT_GE(s->sphericity, std::pow(1 - eps, 2));
  EXPECT_NEAR(s->maximum_3d_diameter_mm, 2 * r, 1e-9);  // the poles are vertices
  EXPECT_NEAR(s->volume_density_convex_hull, 1, 1e-9);  // convex, as the bounds assume

  const double h = 0.25;
  const VolumeShape v = voxel_shape(mesh, grid_over({r, r, r}, h, centre));
  const double tol = variance_tolerance(r, r, h, eps) / 2;  // lengths go as sqrt(variance)
  const double len0 = 4 * r / std::sqrt(5.0);
  for (const double len : {v.major_axis_length_mm, v.minor_axis_length_mm, v.least_axis_length_mm}) {
    EXPECT_NEAR(len, len0, tol * len0);
    RecordProperty("axis_length_relative_error", std::to_string(len / len0 - 1));
  }
  std::printf("sphere r=20: eps %.2e, axis tolerance %.2e, errors %.2e %.2e %.2e\n", eps, tol,
              v.major_axis_length_mm / len0 - 1, v.minor_axis_length_mm / len0 - 1, v.least_axis_length_mm / len0 - 1);
}

TEST(ShapeAnalytic, EllipsoidWithSemiAxes30By20By10) {
  const Vec3 semi{30, 20, 10};
  const TriangleMesh unit = uv_sphere({0, 0, 0}, 1, 200, 400);
  const double eps = inscribed_gap(unit);
  const Vec3 centre{-12.5, 4.25, 101};
  const TriangleMesh mesh = scaled(unit, semi, centre);
  const auto s = surface_shape(mesh);
  ASSERT_TRUE(s.ok()) << s.status().to_string();
  const double v0 = 4 * kPi * semi[0] * semi[1] * semi[2] / 3, a0 = ellipsoid_area(semi[0], semi[1], semi[2]);
  const double psi0 = std::cbrt(36 * kPi * v0 * v0) / a0;
  EXPECT_LE(s->mesh_volume_mm3, v0);
  EXPECT_GE(s->mesh_volume_mm3, v0 * std::pow(1 - eps, 3));
  EXPECT_LE(s->surface_area_mm2, a0);
  EXPECT_GE(s->surface_area_mm2, a0 * std::pow(1 - eps, 2));
  EXPECT_LE(s->sphericity, psi0 / std::pow(1 - eps, 2));
  EXPECT_GE(s->sphericity, psi0 * std::pow(1 - eps, 2));
  EXPECT_NEAR(s->maximum_3d_diameter_mm, 2 * semi[0], 1e-9);  // vertices on the equator at +-a

  const double h = 0.25;
  const VolumeShape v = voxel_shape(mesh, grid_over(semi, h, centre));
  const double lengths[3] = {v.major_axis_length_mm, v.minor_axis_length_mm, v.least_axis_length_mm};
  double var_tol[3];
  for (int a = 0; a < 3; ++a) {
    var_tol[a] = variance_tolerance(semi[a], semi[2], h, eps);
    const double len0 = 4 * semi[a] / std::sqrt(5.0);
    EXPECT_NEAR(lengths[a], len0, var_tol[a] / 2 * len0) << "axis " << a;
    std::printf("ellipsoid axis %d: tolerance %.2e, error %.2e\n", a, var_tol[a] / 2, lengths[a] / len0 - 1);
  }
  // Ratios of two lengths: the relative errors add.
  EXPECT_NEAR(v.elongation, 2.0 / 3, (var_tol[0] + var_tol[1]) / 2 * 2.0 / 3);
  EXPECT_NEAR(v.flatness, 1.0 / 3, (var_tol[0] + var_tol[2]) / 2 * 1.0 / 3);
}

// ---- Invariance under a rigid motion of mesh and grid together. ----

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  double w = g(rng), x = g(rng), y = g(rng), z = g(rng);
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

struct Features {
  VolumeShape volume;
  SurfaceShape surface;       // of the given mesh, box in the grid's axes
  SurfaceShape mask_surface;  // of marching_cubes(mask)
  Maximum2DDiameters diameters;
  double shift_mm = 0;
};

Features features(const TriangleMesh& mesh, const ImageGeometry& g) {
  Features f;
  const auto vox = voxelize_1d(mesh, g);
  EXPECT_TRUE(vox.ok());
  if (!vox.ok()) return f;
  f.volume = *volume_shape(vox->volume);
  f.surface = *surface_shape(mesh, g.direction);
  const auto mask = to_mask(vox->volume);
  const auto mc = marching_cubes(*mask);
  EXPECT_TRUE(mc.ok());
  f.mask_surface = *surface_shape(*mc, g.direction);
  f.diameters = *maximum_2d_diameters(*mc, g);
  // An intensity that depends on the index only, so it moves with the grid.
  Image image{g, std::vector<float>(size_t(g.voxel_count()))};
  for (size_t n = 0; n < image.voxels.size(); ++n) image.voxels[n] = float(1 + n % 7 + (n / 97) % 5);
  f.shift_mm = *centre_of_mass_shift_mm(vox->volume, image);
  return f;
}

TEST(ShapeInvariance, RigidMotionOfMeshAndGridKeepsEveryFeature) {
  std::mt19937_64 rng(11);
  const TriangleMesh mesh = scaled(uv_sphere({0, 0, 0}, 1, 40, 80), {9, 6, 3.5}, {1, 2, 3});
  ImageGeometry g;
  g.spacing_mm = {0.6, 0.5, 0.8};
  g.dims = {40, 36, 20};
  g.origin_mm = {-10.7, -8.9, -4.6};
  const Features a = features(mesh, g);

  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 r = random_rotation(rng);
    std::uniform_real_distribution<double> shift(-200, 200);
    const Vec3 t{shift(rng), shift(rng), shift(rng)};
    TriangleMesh moved = mesh;
    for (auto& v : moved.vertices_mm) v = mul(r, v) + t;
    ImageGeometry mg = g;
    mg.origin_mm = mul(r, g.origin_mm) + t;
    for (int c = 0; c < 3; ++c) {
      const Vec3 axis = mul(r, Vec3{g.direction[0][c], g.direction[1][c], g.direction[2][c]});
      for (int row = 0; row < 3; ++row) mg.direction[row][c] = axis[row];
    }
    const Features b = features(moved, mg);
    // The voxels are the same (the 1D method works in index space, which the motion preserves up
    // to rounding, and no centre lies on the surface), so everything agrees to rounding.
    EXPECT_EQ(a.volume.voxel_count, b.volume.voxel_count);
    const auto same = [](double x, double y, const char* what) { EXPECT_NEAR(x, y, 1e-9 * std::fabs(x)) << what; };
    same(a.volume.major_axis_length_mm, b.volume.major_axis_length_mm, "major");
    same(a.volume.minor_axis_length_mm, b.volume.minor_axis_length_mm, "minor");
    same(a.volume.least_axis_length_mm, b.volume.least_axis_length_mm, "least");
    const Vec3 moved_centroid = mul(r, a.volume.centroid_mm) + t;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.volume.centroid_mm[c], moved_centroid[c], 1e-9);
    const SurfaceShape* sa[2] = {&a.surface, &a.mask_surface};
    const SurfaceShape* sb[2] = {&b.surface, &b.mask_surface};
    for (int m = 0; m < 2; ++m) {
      same(sa[m]->mesh_volume_mm3, sb[m]->mesh_volume_mm3, "volume");
      same(sa[m]->surface_area_mm2, sb[m]->surface_area_mm2, "area");
      same(sa[m]->sphericity, sb[m]->sphericity, "sphericity");
      same(sa[m]->maximum_3d_diameter_mm, sb[m]->maximum_3d_diameter_mm, "3D diameter");
      same(sa[m]->volume_density_aabb, sb[m]->volume_density_aabb, "volume density aabb");
      same(sa[m]->area_density_aabb, sb[m]->area_density_aabb, "area density aabb");
      same(sa[m]->volume_density_convex_hull, sb[m]->volume_density_convex_hull, "volume density hull");
      same(sa[m]->area_density_convex_hull, sb[m]->area_density_convex_hull, "area density hull");
    }
    same(a.diameters.slice_mm, b.diameters.slice_mm, "slice");
    same(a.diameters.column_mm, b.diameters.column_mm, "column");
    same(a.diameters.row_mm, b.diameters.row_mm, "row");
    EXPECT_NEAR(a.shift_mm, b.shift_mm, 1e-9);
  }
}

}  // namespace
}  // namespace soiq
