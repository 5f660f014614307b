#include "core/voxelize/voxelize_1d.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/base/parallel_for.h"
#include "core/base/run_tasks.h"
#include "core/geometry/exact_predicates.h"
#include "core/voxelize/line_fill.h"
#include "core/voxelize/three_axis_vote.h"

namespace soiq {

namespace {

// A mesh in continuous index space of a grid scanned along its first axis: voxel centres at
// integers, rows are the lines {(x, j, k)}. Coordinates are split per axis (structure of arrays)
// because the lattice walk reads y and z far more often than x.
struct ScanProblem {
  std::vector<double> x, y, z;
  const std::vector<std::array<int32_t, 3>>* triangles = nullptr;
  int64_t nx = 0, ny = 0, nz = 0;
  FillRule rule = FillRule::kNonZero;
};

// One directed edge a -> b of a triangle's (y,z) projection. Its edge function at a lattice point
// P = (j,k) is orient2d(a, b, P); its sign is exact (core/geometry/exact_predicates), so the two triangles
// sharing the edge (which run it in opposite directions) always see opposite signs, and an exact
// zero takes the sign of the symbolic perturbation of P to (j + e, k + e^2). No lattice point is
// ever on an edge, and every edge puts it on exactly one side for both triangles: that is the whole
// watertightness argument, with no epsilon.
struct ProjectedEdge {
  double a_y, a_z, b_y, b_z, dy, dz;
  int tie_sign;  // the perturbed sign where the exact value is 0; 0 for a zero-length edge

  ProjectedEdge(double ay, double az, double by, double bz) : a_y(ay), a_z(az), b_y(by), b_z(bz) {
    dy = by - ay;
    dz = bz - az;
    // E(P + (e, e^2)) = E(P) - dz*e + dy*e^2.
    tie_sign = dz != 0 ? (dz > 0 ? -1 : 1) : (dy > 0) - (dy < 0);
  }

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
    if (error == 0 || (py == a_y && pz == a_z) || (py == b_y && pz == b_z)) return {0.0, 0.0, tie_sign};
    const int exact = orient2d_sign_exact(a_y, a_z, b_y, b_z, py, pz);
    return {value, error, exact != 0 ? exact : tie_sign};
  }
};

// The slabs of slices that threads fill independently: slab s is [k_begin(s), k_begin(s+1)).
struct Slabs {
  int64_t count = 1;
  int64_t nz = 0;
  int64_t k_begin(int64_t s) const { return nz * s / count; }
  int64_t of_slice(int64_t k) const { return ((k + 1) * count - 1) / nz; }  // inverse of k_begin
};

// The lattice slices each triangle reaches, and, with several slabs, the triangles each slab must
// visit, in one flat array grouped by slab: counted, then placed, both passes in parallel over
// chunks of triangles, so no slab ever scans every triangle, nothing grows, and no serial sort
// stands in front of the threads. Within a slab the order follows the chunks; it is irrelevant:
// crossings are grouped by line and sorted afterwards.
struct SlabTriangles {
  std::unique_ptr<int32_t[]> k_first, k_last;  // per triangle, clamped; first > last = none
  std::vector<int32_t> order;                  // slab s: order[slab_start[s] .. slab_start[s+1])
  std::vector<int64_t> slab_start;             // empty with one slab: every triangle is visited
};

SlabTriangles triangles_by_slab(const ScanProblem& p, const Slabs& slabs, int threads) {
  const auto& tris = *p.triangles;
  const size_t n = tris.size();
  SlabTriangles b;
  // Not zero-filled: each chunk writes its own triangles, so pages are first touched in parallel.
  b.k_first.reset(new int32_t[n]);
  b.k_last.reset(new int32_t[n]);
  const int64_t chunks = slabs.count > 1 ? std::max(threads, 1) : 1;
  const int64_t nslabs = slabs.count;
  // count[c * nslabs + s]: triangles of chunk c reaching slab s; then their first place in `order`.
  std::vector<int64_t> count(size_t(chunks * nslabs), 0);
  const double last_slice = double(p.nz - 1);
  // Slab of each slice, looked up: a 64-bit division per triangle end cost more than the counting.
  std::vector<int32_t> slab_of(size_t(nslabs > 1 ? p.nz : 0));
  for (int64_t k = 0; k < int64_t(slab_of.size()); ++k) slab_of[size_t(k)] = int32_t(slabs.of_slice(k));
  auto chunk_range = [&](int64_t c) {
    return std::pair<size_t, size_t>(n * size_t(c) / size_t(chunks), n * size_t(c + 1) / size_t(chunks));
  };
  run_tasks(chunks, int(chunks), [&](int64_t c) {
    const auto [begin, end] = chunk_range(c);
    // Counted locally and stored once: neighbouring chunks' counts share cache lines.
    std::vector<int64_t> mine(size_t(nslabs), 0);
    for (size_t t = begin; t < end; ++t) {
      const double z0 = p.z[size_t(tris[t][0])], z1 = p.z[size_t(tris[t][1])], z2 = p.z[size_t(tris[t][2])];
      const double lo = std::max(std::ceil(std::min({z0, z1, z2})), 0.0);
      const double hi = std::min(std::floor(std::max({z0, z1, z2})), last_slice);
      const bool any = lo <= hi;
      b.k_first[t] = any ? int32_t(lo) : 1;
      b.k_last[t] = any ? int32_t(hi) : 0;
      if (!any || nslabs == 1) continue;
      for (int32_t s = slab_of[size_t(lo)]; s <= slab_of[size_t(hi)]; ++s) ++mine[size_t(s)];
    }
    std::copy(mine.begin(), mine.end(), count.begin() + c * nslabs);
  });
  if (nslabs == 1) return b;
  b.slab_start.assign(size_t(nslabs + 1), 0);
  int64_t at = 0;
  for (int64_t s = 0; s < nslabs; ++s) {
    b.slab_start[size_t(s)] = at;
    for (int64_t c = 0; c < chunks; ++c) {
      const int64_t k = count[size_t(c * nslabs + s)];
      count[size_t(c * nslabs + s)] = at;
      at += k;
    }
  }
  b.slab_start[size_t(nslabs)] = at;
  b.order.resize(size_t(at));
  run_tasks(chunks, int(chunks), [&](int64_t c) {
    const auto [begin, end] = chunk_range(c);
    std::vector<int64_t> next(count.begin() + c * nslabs, count.begin() + (c + 1) * nslabs);
    for (size_t t = begin; t < end; ++t) {
      if (b.k_first[t] > b.k_last[t]) continue;
      for (int32_t s = slab_of[size_t(b.k_first[t])]; s <= slab_of[size_t(b.k_last[t])]; ++s)
        b.order[size_t(next[size_t(s)]++)] = int32_t(t);
    }
  });
  return b;
}

// The first voxel centre at or after the crossing of line (j,k) with the plane of triangle abc
// (index space, vertices v[0..2]); `x` is the interpolated crossing, `tolerance` a bound on its
// error, `normal_x_sign` the exact sign of the normal's x component. When x is within tolerance
// of an integer, the side of that integer is decided exactly by orient3d: the half-open rule
// (a centre exactly on an entering crossing is inside) then holds to the last bit.
int64_t first_centre(const double (&v)[3][3], double x, double tolerance, int normal_x_sign, int64_t j, int64_t k,
                     int64_t nx) {
  const double nearest = std::nearbyint(x);
  if (std::abs(x - nearest) > tolerance) return clamped_ceil(x, nx);
  // Smallest integer m with x_exact <= m, by bisection over the integers that tolerance admits
  // (one or two predicates in practice). n . ((m,j,k) - a) = n_x (m - x_exact).
  auto at_or_after = [&](double m) {
    const double q[3] = {m, double(j), double(k)};
    return orient3d_sign(v[0], v[1], v[2], q) * normal_x_sign >= 0;
  };
  double lo = std::max(std::floor(x - tolerance) - 1, -2.0);           // x_exact > lo
  double hi = std::min(std::ceil(x + tolerance) + 1, double(nx + 2));  // x_exact <= hi
  // Should the bound ever be too tight, widen to the whole line rather than guess.
  if (at_or_after(lo)) {
    if (lo <= -2 || at_or_after(-2.0)) return -1;
    hi = lo;
    lo = -2;
  }
  if (!at_or_after(hi)) {
    if (hi >= double(nx + 2) || !at_or_after(double(nx + 2))) return nx + 1;
    lo = hi;
    hi = double(nx + 2);
  }
  while (hi - lo > 1) {
    const double mid = std::floor((lo + hi) / 2);
    (at_or_after(mid) ? hi : lo) = mid;
  }
  return clamped_ceil(hi, nx);
}

// Appends the crossings of triangle t with the row lines of slices [k_lo, k_hi].
void triangle_crossings(const ScanProblem& p, const std::array<int32_t, 3>& tri, int64_t k_lo, int64_t k_hi, int64_t k0,
                        std::vector<LineCrossingAt>& out) {
  const size_t a = size_t(tri[0]), b = size_t(tri[1]), c = size_t(tri[2]);
  const double ymin = std::min({p.y[a], p.y[b], p.y[c]}), ymax = std::max({p.y[a], p.y[b], p.y[c]});
  const int64_t j_lo = int64_t(std::max(std::ceil(ymin), 0.0));
  const int64_t j_hi = int64_t(std::min(std::floor(ymax), double(p.ny - 1)));
  if (j_lo > j_hi) return;
  // A triangle whose (y,z) projection has zero area (edge-on to the rows: every face of a
  // marching-cubes surface parallel to x) contains no perturbed lattice point: skip it before any
  // lattice work. The area is the exact orient2d of its projected vertices.
  if (orient2d_sign(p.y[a], p.z[a], p.y[b], p.z[b], p.y[c], p.z[c]) == 0) return;
  const ProjectedEdge ab(p.y[a], p.z[a], p.y[b], p.z[b]);
  const ProjectedEdge bc(p.y[b], p.z[b], p.y[c], p.z[c]);
  const ProjectedEdge ca(p.y[c], p.z[c], p.y[a], p.z[a]);
  const double v[3][3] = {{p.x[a], p.y[a], p.z[a]}, {p.x[b], p.y[b], p.z[b]}, {p.x[c], p.y[c], p.z[c]}};
  constexpr double kEps = 1.1102230246251565e-16;
  for (int64_t k = k_lo; k <= k_hi; ++k) {
    const double pz = double(k);
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
      // it only decides when the exact orient3d test is consulted).
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
      const int normal_x_sign = e_c.sign;
      out.push_back({j + p.ny * (k - k0),
                     {first_centre(v, x, tolerance, normal_x_sign, j, k, p.nx), normal_x_sign > 0 ? -1 : 1}});
    }
  }
}

LineRuns scan_slab(const ScanProblem& p, const SlabTriangles& slab_triangles, int64_t slab, int64_t k0, int64_t k1,
                   bool drop_unbalanced) {
  const auto& tris = *p.triangles;
  // Each thread keeps its crossing buffer from one slab and conversion to the next: a fresh
  // megabyte-sized buffer per slab came from mmap (or a trimmed arena) each time, and its page
  // faults made whole processes run 2-thread conversions at 1-thread speed.
  thread_local std::vector<LineCrossingAt> crossings;
  crossings.clear();
  // Enough for a closed surface crossing each line it reaches a few times, so growth (a copy of
  // every crossing) is rare.
  crossings.reserve(size_t(std::max<int64_t>(4 * p.ny * (k1 - k0), int64_t(tris.size()) / 2)));
  auto visit = [&](size_t t) {
    if (slab_triangles.k_last[t] < k0 || slab_triangles.k_first[t] >= k1) return;
    triangle_crossings(p, tris[t], std::max<int64_t>(slab_triangles.k_first[t], k0),
                       std::min<int64_t>(slab_triangles.k_last[t], k1 - 1), k0, crossings);
  };
  if (slab_triangles.slab_start.empty()) {
    for (size_t t = 0; t < tris.size(); ++t) visit(t);
  } else {
    for (int64_t i = slab_triangles.slab_start[size_t(slab)]; i < slab_triangles.slab_start[size_t(slab + 1)]; ++i)
      visit(size_t(slab_triangles.order[size_t(i)]));
  }
  return fill_lines(crossings, p.ny * (k1 - k0), p.nx, p.rule, drop_unbalanced);
}

// Scans every row line of the grid, slabs of slices in parallel, and concatenates the slabs in
// slice order, so the result does not depend on the thread count.
LineRuns scan(const ScanProblem& p, int threads, bool drop_unbalanced) {
  Slabs slabs;
  slabs.nz = p.nz;
  // Two slabs per thread: a slab heavy with surface does not leave the other threads idle, and few
  // slabs keep the per-slab costs (bucketing, merging) small (4 per thread was 7 % slower on SM1).
  slabs.count = std::max<int64_t>(1, std::min<int64_t>(p.nz, threads <= 1 ? 1 : int64_t(threads) * 2));
  const SlabTriangles slab_triangles = triangles_by_slab(p, slabs, threads);
  std::vector<LineRuns> results(static_cast<size_t>(slabs.count));
  // Slabs are handed out one at a time, so a slab heavy with surface does not hold up the rest.
  run_tasks(slabs.count, threads, [&](int64_t s) {
    results[size_t(s)] = scan_slab(p, slab_triangles, s, slabs.k_begin(s), slabs.k_begin(s + 1), drop_unbalanced);
  });
  if (slabs.count == 1) return std::move(results[0]);
  // Concatenate in slice order; each slab copies its own part in parallel.
  std::vector<int64_t> run_base(size_t(slabs.count + 1), 0);
  LineRuns out;
  for (int64_t s = 0; s < slabs.count; ++s) {
    run_base[size_t(s + 1)] = run_base[size_t(s)] + int64_t(results[size_t(s)].runs.size());
    out.unbalanced_lines += results[size_t(s)].unbalanced_lines;
  }
  out.runs.resize(size_t(run_base.back()));
  out.line_start.resize(size_t(p.ny * p.nz + 1));
  parallel_for(
      slabs.count, threads,
      [&](int64_t first, int64_t last) {
        for (int64_t s = first; s < last; ++s) {
          const LineRuns& r = results[size_t(s)];
          const int64_t line0 = p.ny * slabs.k_begin(s);
          for (size_t l = 0; l + 1 < r.line_start.size(); ++l) {
            out.line_start[size_t(line0) + l] = run_base[size_t(s)] + r.line_start[l];
          }
          std::copy(r.runs.begin(), r.runs.end(), out.runs.begin() + run_base[size_t(s)]);
        }
      },
      1);
  out.line_start.back() = run_base.back();
  return out;
}

// The mesh in index space of `g`, scanned along `axis` (0 = i, 1 = j, 2 = k). The other two axes
// follow cyclically, (axis, axis+1, axis+2), a rotation that keeps the handedness and so the
// meaning of the crossing signs.
ScanProblem index_space_problem(const TriangleMesh& mesh, const ImageGeometry& g, int axis, FillRule rule,
                                int threads) {
  ScanProblem p;
  const size_t n = mesh.vertices_mm.size();
  p.x.resize(n);
  p.y.resize(n);
  p.z.resize(n);
  parallel_for(int64_t(n), threads, [&](int64_t begin, int64_t end) {
    for (size_t v = size_t(begin); v < size_t(end); ++v) {
      const Vec3 u = g.physical_to_index(mesh.vertices_mm[v]);
      p.x[v] = u[size_t(axis)];
      p.y[v] = u[size_t((axis + 1) % 3)];
      p.z[v] = u[size_t((axis + 2) % 3)];
    }
  });
  p.triangles = &mesh.triangles;
  p.nx = g.dims[size_t(axis)];
  p.ny = g.dims[size_t((axis + 1) % 3)];
  p.nz = g.dims[size_t((axis + 2) % 3)];
  p.rule = rule;
  return p;
}

}  // namespace

Result<Voxelization> voxelize_1d(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                 const VoxelizeOptions& options) {
  const std::string name = options.name ? options.name : "mesh";
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, options.max_voxels));
  if (geometry.dims[0] > INT32_MAX - 2) return invalid_argument("grid rows longer than 2^31 voxels are not supported");
  Voxelization out;
  out.defects = options.known_defects ? *options.known_defects : mesh_defects(mesh);
  SOIQ_RETURN_IF_ERROR(validate_mesh(mesh, out.defects, name));
  if (!options.robust && !out.defects.closed()) {
    return failed_precondition("mesh '" + name + "' is not closed and consistently oriented (" + describe(out.defects) +
                               "); use robust mode (--robust) or repair the mesh");
  }
  if (geometry.voxel_count() == 0) {
    out.volume = empty_volume(geometry);
    return out;
  }
  const int threads = std::max(1, options.threads);
  if (!options.robust) {
    LineRuns r = scan(index_space_problem(mesh, geometry, 0, options.fill_rule, threads), threads, false);
    if (r.unbalanced_lines > 0) {
      return internal_error("mesh '" + name + "' passed the closedness check but " +
                            std::to_string(r.unbalanced_lines) +
                            " row lines cross it an unbalanced number of times; please report this mesh");
    }
    out.volume.geometry = geometry;
    out.volume.line_start = std::move(r.line_start);
    out.volume.runs = std::move(r.runs);
    return out;
  }
  // Robust mode: fill along each of the three axes; lines that cross an open surface an unbalanced
  // number of times abstain (vote outside); a voxel is kept when two of the three fills agree.
  std::array<AxisRuns, 3> fills;
  for (int axis = 0; axis < 3; ++axis) {
    LineRuns r = scan(index_space_problem(mesh, geometry, axis, options.fill_rule, threads), threads, true);
    fills[size_t(axis)] = {std::move(r.line_start), std::move(r.runs)};
  }
  out.volume = three_axis_vote(geometry, fills);
  return out;
}

}  // namespace soiq
