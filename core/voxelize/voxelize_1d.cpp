#include "core/voxelize/voxelize_1d.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/base/cpu_dispatch.h"
#include "core/base/parallel_for.h"
#include "core/base/run_tasks.h"
#include "core/geometry/exact_predicates.h"
#include "core/voxelize/crossing_buffers.h"
#include "core/voxelize/line_fill.h"
#include "core/voxelize/scan_lattice.h"
#include "core/voxelize/three_axis_vote.h"

namespace soiq {

namespace {

using scanline::index_space_problem;
using scanline::ScanProblem;
using scanline::Slabs;

// The first voxel centre at or after the crossing of line (j,k) with the plane of triangle abc
// (index space, vertices v[0..2]); `x` is the interpolated crossing, `tolerance` a bound on its
// error, `normal_x_sign` the exact sign of the normal's x component. When x is within tolerance
// of an integer, the side of that integer is decided exactly by orient3d: the half-open rule
// (a centre exactly on an entering crossing is inside) then holds to the last bit.
int64_t first_centre(const double (&v)[3][3], double x, double tolerance, int normal_x_sign, int64_t j, double z,
                     int64_t nx) {
  const double nearest = std::nearbyint(x);
  if (std::abs(x - nearest) > tolerance) return clamped_ceil(x, nx);
  // Smallest integer m with x_exact <= m, by bisection over the integers that tolerance admits
  // (one or two predicates in practice). n . ((m,j,k) - a) = n_x (m - x_exact).
  auto at_or_after = [&](double m) {
    const double q[3] = {m, double(j), z};
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
  scanline::for_each_hit(p, tri, k_lo, k_hi, [&](const scanline::LineHit& h) {
    out.push_back(
        {h.j + p.ny * (h.k - k0),
         {first_centre(h.v, h.x, h.tolerance, h.normal_x_sign, h.j, h.z, p.nx), h.normal_x_sign > 0 ? -1 : 1}});
  });
}

// Every row line of slices [k0, k1) from the triangles they reach, on one thread; lines numbered
// from slice k0.
LineRuns scan_slices(const ScanProblem& p, int64_t k0, int64_t k1, bool drop_unbalanced) {
  const auto& tris = *p.triangles;
  // Each thread keeps its crossing buffer from one conversion to the next: a fresh megabyte-sized
  // buffer each time came from mmap (or a trimmed arena), and its page faults cost as much as the
  // walk.
  thread_local std::vector<LineCrossingAt> crossings;
  crossings.clear();
  // Enough for a closed surface crossing each line it reaches a few times, so growth (a copy of
  // every crossing) is rare.
  crossings.reserve(size_t(std::max<int64_t>(4 * p.ny * (k1 - k0), int64_t(tris.size()) / 2)));
  for (const auto& tri : tris) triangle_crossings(p, tri, k0, k1 - 1, k0, crossings);
  return fill_lines(crossings, p.ny * (k1 - k0), p.nx, p.rule, drop_unbalanced);
}

// Scans every row line of the grid. With several threads, each walks an equal share of the
// triangles over the whole grid, then each fills the lines of one slab of slices from every
// share's crossings there, and the slabs are concatenated in slice order. A triangle is visited
// once, by one thread, with no pass sorting triangles into slabs first (two more passes over every
// triangle), and a slab heavy with surface costs only its fill, which is small. The crossings of a
// line come in triangle order either way, so the result does not depend on the thread count.
LineRuns scan(const ScanProblem& p, int threads, bool drop_unbalanced) {
  if (threads <= 1 || p.nz < 2) {
    return cpu_dispatch([&] { return scan_slices(p, 0, p.nz, drop_unbalanced); });
  }
  const auto& tris = *p.triangles;
  const int64_t shares = threads;
  std::vector<CrossingBufferLease> found(static_cast<size_t>(shares));
  run_tasks(shares, threads, [&](int64_t c) {
    cpu_dispatch([&] {
      std::vector<LineCrossingAt>& out = *found[size_t(c)];
      const size_t begin = tris.size() * size_t(c) / size_t(shares), end = tris.size() * size_t(c + 1) / size_t(shares);
      out.reserve(size_t(std::max<int64_t>(4 * p.ny * p.nz / shares, int64_t(end - begin) / 2)));
      for (size_t t = begin; t < end; ++t) triangle_crossings(p, tris[t], 0, p.nz - 1, 0, out);
    });
  });
  Slabs slabs;
  slabs.nz = p.nz;
  slabs.count = std::min<int64_t>(p.nz, threads);
  std::vector<const std::vector<LineCrossingAt>*> parts;
  for (CrossingBufferLease& share : found) parts.push_back(&*share);
  std::vector<LineRuns> results(static_cast<size_t>(slabs.count));
  run_tasks(slabs.count, threads, [&](int64_t s) {
    const int64_t first_line = p.ny * slabs.k_begin(s), end_line = p.ny * slabs.k_begin(s + 1);
    results[size_t(s)] = fill_lines(parts, first_line, end_line - first_line, p.nx, p.rule, drop_unbalanced);
  });
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
  SOIQ_RETURN_IF_ERROR(scanline::scan_supported(geometry, 1, 1, "robust conversion (a vote of three axes)"));
  std::array<AxisRuns, 3> fills;
  for (int axis = 0; axis < 3; ++axis) {
    LineRuns r = scan(index_space_problem(mesh, geometry, axis, options.fill_rule, threads), threads, true);
    fills[size_t(axis)] = {std::move(r.line_start), std::move(r.runs)};
  }
  out.volume = three_axis_vote(geometry, fills);
  return out;
}

}  // namespace soiq
