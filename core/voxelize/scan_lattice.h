#pragma once
// The lattice walk shared by the 1D method (voxelize_1d.h) and its coverage fractions
// (coverage_1d.h): a mesh in the continuous index space of a grid scanned along one axis, the slabs
// of slices threads scan apart, and, per triangle, every row line whose lattice point its (y,z)
// projection contains, with the interpolated crossing. Both methods share it so that they decide
// "does this line cross this triangle" identically (docs/DESIGN.md, "The 1D method, precisely").
// Internal to core/voxelize.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/base/fill_rule.h"
#include "core/base/image_geometry.h"
#include "core/base/triangle_mesh.h"
#include "core/geometry/exact_predicates.h"

namespace soiq::scanline {

// A mesh in continuous index space of a grid scanned along its first axis: voxel centres at
// integers, rows are the lines {(x, j, k)}. A vertex's three coordinates lie together: the walk
// reads a triangle's vertices in the order of its indices, and one cache line per vertex (rather
// than one per axis) was 10 % of a conversion.
// An unevenly spaced grid's slices are not at integer z: slice_z holds each one's lattice z
// (ImageGeometry::lattice_z), and rows are the lines {(x, j, slice_z[k])}.
struct ScanProblem {
  std::vector<Vec3> xyz;
  const std::vector<std::array<int32_t, 3>>* triangles = nullptr;
  int64_t nx = 0, ny = 0, nz = 0;
  FillRule rule = FillRule::kNonZero;
  std::vector<double> slice_z;  // empty: slice k at z = k

  double plane_z(int64_t k) const { return slice_z.empty() ? double(k) : slice_z[size_t(k)]; }
};

// One directed edge a -> b of a triangle's (y,z) projection. Its edge function at a lattice point
// P = (j,k) is orient2d(a, b, P); its sign is exact (core/geometry/exact_predicates), so the two triangles
// sharing the edge (which run it in opposite directions) always see opposite signs, and an exact
// zero takes the sign of the symbolic perturbation of P to (j + e, k + e^2). No lattice point is
// ever on an edge, and every edge puts it on exactly one side for both triangles: that is the whole
// watertightness argument, with no epsilon.
struct ProjectedEdge {
  double a_y, a_z, b_y, b_z, dy, dz;

  ProjectedEdge(double ay, double az, double by, double bz)
      : a_y(ay), a_z(az), b_y(by), b_z(bz), dy(by - ay), dz(bz - az) {}

  // The perturbed sign where the exact value is 0; 0 for a zero-length edge. Asked only at exact
  // zeros, so it is not worked out per triangle.
  // E(P + (e, e^2)) = E(P) - dz*e + dy*e^2.
  int tie_sign() const { return dz != 0 ? (dz > 0 ? -1 : 1) : (dy > 0) - (dy < 0); }

  struct Value {
    double value;  // the edge function in double
    double error;  // a bound on |value - exact value|
    int sign;      // the exact perturbed sign: never 0
  };

  // The part of the edge function that depends on the slice only: computed once per row.
  double slice_term(double pz) const { return dy * (pz - a_z); }

  // The edge function at (py, pz), given t1 = slice_term(pz).
  Value at(double t1, double py, double pz) const {
    const double t2 = dz * (py - a_y);
    const double value = t1 - t2;
    const double error = orient2d_error_bound(t1, t2);
    if (value > error) return {value, error, 1};
    if (value < -error) return {value, error, -1};
    // Near or at zero. Both products exactly 0, or the lattice point on an endpoint (every
    // marching-cubes vertex on a row line), is an exact zero without arithmetic; anything else
    // asks the exact predicate.
    if (error == 0 || (py == a_y && pz == a_z) || (py == b_y && pz == b_z)) return {0.0, 0.0, tie_sign()};
    const int exact = orient2d_sign_exact(a_y, a_z, b_y, b_z, py, pz);
    return {value, error, exact != 0 ? exact : tie_sign()};
  }
};

// The slabs of slices that threads fill independently: slab s is [k_begin(s), k_begin(s+1)).
struct Slabs {
  int64_t count = 1;
  int64_t nz = 0;
  int64_t k_begin(int64_t s) const { return nz * s / count; }
  int64_t of_slice(int64_t k) const { return ((k + 1) * count - 1) / nz; }  // inverse of k_begin
};

// The lattice slices a triangle with vertex z's z0, z1, z2 reaches: those whose row lines' z
// (p.plane_z) lies in its z range, ends included, clamped to the grid; first > last when none.
struct SliceRange {
  int64_t first, last;
};
inline SliceRange slice_range(const ScanProblem& p, double z0, double z1, double z2) {
  const double zmin = std::min({z0, z1, z2}), zmax = std::max({z0, z1, z2});
  if (p.slice_z.empty()) {
    return {int64_t(std::max(std::ceil(zmin), 0.0)), int64_t(std::min(std::floor(zmax), double(p.nz - 1)))};
  }
  const auto& sz = p.slice_z;
  return {std::lower_bound(sz.begin(), sz.end(), zmin) - sz.begin(),
          (std::upper_bound(sz.begin(), sz.end(), zmax) - sz.begin()) - 1};
}

// Coverage fractions (coverage_1d.h), whose slices each need all their triangles at once: with
// several slabs, the triangles each slab must visit, in one flat array grouped by slab:
// counted, then placed, both passes in parallel over chunks of triangles, so no slab ever scans
// every triangle, nothing grows, and no serial sort stands in front of the threads. Within a slab
// the order follows the chunks; it is irrelevant: crossings are grouped by line and sorted
// afterwards. With one slab nothing is built (and no pass made): the slab visits every triangle.
struct SlabTriangles {
  std::vector<int32_t> order;       // slab s: order[slab_start[s] .. slab_start[s+1])
  std::vector<int64_t> slab_start;  // empty with one slab: every triangle is visited

  // Calls visit(t) for each triangle t that slab s must visit, of `triangle_count` in all.
  template <typename Visit>
  void for_each_in_slab(int64_t s, size_t triangle_count, Visit&& visit) const {
    if (slab_start.empty()) {
      for (size_t t = 0; t < triangle_count; ++t) visit(t);
      return;
    }
    for (int64_t i = slab_start[size_t(s)]; i < slab_start[size_t(s + 1)]; ++i) visit(size_t(order[size_t(i)]));
  }
};

SlabTriangles triangles_by_slab(const ScanProblem& p, const Slabs& slabs, int threads);

// The mesh in index space of `g` (its lattice, for an unevenly spaced grid: then only along i and
// with one line per voxel, which callers check with scan_supported), scanned along `axis` (0 = i,
// 1 = j, 2 = k). The other two axes
// follow cyclically, (axis, axis+1, axis+2), a rotation that keeps the handedness and so the
// meaning of the crossing signs. With `lines_per_voxel` n > 1 the two cross axes are scaled so that
// the lattice holds n x n lines per voxel, at the centres of an n x n split of its cross-section:
// line (j', k') = (n j + a, n k + b) runs through (j - 1/2 + (a + 1/2)/n, k - 1/2 + (b + 1/2)/n).
ScanProblem index_space_problem(const TriangleMesh& mesh, const ImageGeometry& g, int axis, FillRule rule, int threads,
                                int lines_per_voxel = 1);

// OK unless `g` is unevenly spaced and the scan would run along another axis than i or sample a
// voxel by more than one line: the rows of such a grid are not evenly spaced along k, so the
// voxel centres would not be integers along the scan, nor a voxel's cross-section a square of
// lines. FAILED_PRECONDITION naming `what` (the method) otherwise.
Status scan_supported(const ImageGeometry& g, int axis, int lines_per_voxel, const char* what);

// Where row line (j,k) crosses a triangle: x interpolated in double (exact for a line through a
// vertex), `tolerance` a bound on its error, `normal_x_sign` the exact sign of the triangle
// normal's x component (+1: the line leaves the surface there), `v` the triangle in index space.
struct LineHit {
  int64_t j, k;
  double z;  // the line's lattice z: p.plane_z(k)
  double x, tolerance;
  int normal_x_sign;
  const double (&v)[3][3];
};

// Calls on_hit(const LineHit&) for every row line (j,k), k in [k_lo, k_hi], whose perturbed lattice
// point (j + e, k + e^2) lies inside the (y,z) projection of `tri`. Defined here so that each
// caller's on_hit inlines into the hot loop (and, under cpu_dispatch, is compiled for the CPU).
// Most triangles of a fine surface hold no lattice point: the cheapest tests that find so come
// first (the y range, then the z range), before any per-edge work.
template <typename OnHit>
void for_each_hit(const ScanProblem& p, const std::array<int32_t, 3>& tri, int64_t k_lo, int64_t k_hi, OnHit&& on_hit) {
  const Vec3 &va = p.xyz[size_t(tri[0])], &vb = p.xyz[size_t(tri[1])], &vc = p.xyz[size_t(tri[2])];
  const double ymin = std::min({va[1], vb[1], vc[1]}), ymax = std::max({va[1], vb[1], vc[1]});
  const int64_t j_lo = int64_t(std::max(std::ceil(ymin), 0.0));
  const int64_t j_hi = int64_t(std::min(std::floor(ymax), double(p.ny - 1)));
  if (j_lo > j_hi) return;
  const SliceRange slices = slice_range(p, va[2], vb[2], vc[2]);
  k_lo = std::max(k_lo, slices.first);
  k_hi = std::min(k_hi, slices.last);
  if (k_lo > k_hi) return;
  // A triangle whose (y,z) projection has zero area (edge-on to the rows: every face of a
  // marching-cubes surface parallel to x) contains no perturbed lattice point: skip it before any
  // lattice work. The area is the exact orient2d of its projected vertices.
  {
    const double t1 = (vb[1] - va[1]) * (vc[2] - va[2]), t2 = (vb[2] - va[2]) * (vc[1] - va[1]);
    if (orient2d_sign_filtered(t1 - t2, orient2d_error_bound(t1, t2), va[1], va[2], vb[1], vb[2], vc[1], vc[2]) == 0)
      return;
  }
  const ProjectedEdge ab(va[1], va[2], vb[1], vb[2]);
  const ProjectedEdge bc(vb[1], vb[2], vc[1], vc[2]);
  const ProjectedEdge ca(vc[1], vc[2], va[1], va[2]);
  const double v[3][3] = {{va[0], va[1], va[2]}, {vb[0], vb[1], vb[2]}, {vc[0], vc[1], vc[2]}};
  constexpr double kEps = 1.1102230246251565e-16;
  for (int64_t k = k_lo; k <= k_hi; ++k) {
    const double pz = p.plane_z(k);
    const double t_ab = ab.slice_term(pz), t_bc = bc.slice_term(pz), t_ca = ca.slice_term(pz);
    for (int64_t j = j_lo; j <= j_hi; ++j) {
      const double py = double(j);
      const ProjectedEdge::Value e_c = ab.at(t_ab, py, pz);
      const ProjectedEdge::Value e_a = bc.at(t_bc, py, pz);
      if (e_a.sign != e_c.sign) continue;
      const ProjectedEdge::Value e_b = ca.at(t_ca, py, pz);
      if (e_b.sign != e_c.sign) continue;
      // Barycentric interpolation with the edge functions as weights, written as the heaviest
      // vertex plus weighted differences, so a line through a vertex (the other weights exactly
      // 0) gets exactly that vertex's x.
      const double w[3] = {e_a.value, e_b.value, e_c.value};
      const double err[3] = {e_a.error, e_b.error, e_c.error};
      const double sum = w[0] + w[1] + w[2];
      const int base = (std::abs(w[0]) >= std::abs(w[1]) && std::abs(w[0]) >= std::abs(w[2]))
                           ? 0
                           : (std::abs(w[1]) >= std::abs(w[2]) ? 1 : 2);
      const int o1 = (base + 1) % 3, o2 = (base + 2) % 3;
      const double d1 = v[o1][0] - v[base][0], d2 = v[o2][0] - v[base][0];
      const double numerator = w[o1] * d1 + w[o2] * d2;
      const double x = v[base][0] + numerator / sum;
      // A bound on x's error from the weights' bounds and the few roundings in between (generous:
      // it only decides when the exact orient3d test is consulted). A caller that does not read it
      // does not pay for it: on_hit inlines and the arithmetic is dead.
      const double sum_error = err[0] + err[1] + err[2] + 4 * kEps * (std::abs(w[0]) + std::abs(w[1]) + std::abs(w[2]));
      double tolerance = HUGE_VAL;
      if (std::abs(sum) > 2 * sum_error) {
        const double num_error =
            err[o1] * std::abs(d1) + err[o2] * std::abs(d2) + 4 * kEps * (std::abs(w[o1] * d1) + std::abs(w[o2] * d2));
        const double ratio = std::abs(numerator / sum);
        tolerance =
            2 * (num_error + ratio * sum_error) / (std::abs(sum) - sum_error) + 8 * kEps * (std::abs(x) + ratio + 1);
      }
      // All weights positive: counter-clockwise in (y,z), normal along +x, so the line leaves.
      on_hit(LineHit{j, k, pz, x, tolerance, e_c.sign, v});
    }
  }
}

}  // namespace soiq::scanline
