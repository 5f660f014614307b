#include "core/voxelize_1d.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "core/line_fill.h"
#include "core/parallel_for.h"
#include "core/three_axis_vote.h"

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

// One edge of a triangle's (y,z) projection, set up so that the two triangles sharing it compute
// bit-identical edge functions of opposite sign: the function is always evaluated from the
// lexicographically smaller endpoint and then multiplied by `flip`. That, and the symbolic
// perturbation of the sample point to (j + e, k + e^2), is the whole watertightness argument:
// no sample point is on an edge, and each edge puts it on exactly one side for both triangles.
struct ProjectedEdge {
  double lo_y, lo_z, dy, dz;
  int flip;      // +1 when the triangle runs lo -> hi, -1 when hi -> lo
  int tie_sign;  // the perturbed sign when the exact value is 0, already multiplied by flip

  ProjectedEdge(double ay, double az, double by, double bz) {
    flip = 1;
    if (by < ay || (by == ay && bz < az)) {
      std::swap(ay, by);
      std::swap(az, bz);
      flip = -1;
    }
    lo_y = ay;
    lo_z = az;
    dy = by - ay;
    dz = bz - az;
    // E(P + (e, e^2)) = E(P) - dz*e + dy*e^2; lo < hi makes dy > 0 whenever dz == 0.
    const int canonical_tie = dz != 0 ? (dz > 0 ? -1 : 1) : 1;
    tie_sign = canonical_tie * flip;
  }
  // The edge function at (py, pz), oriented as the triangle runs.
  double value(double py, double pz) const { return flip * (dy * (pz - lo_z) - dz * (py - lo_y)); }
  static int sign_of(double v, int tie) { return v > 0 ? 1 : (v < 0 ? -1 : tie); }
};

// The lattice slices each triangle reaches, and the triangle indices sorted by their first slice
// (a counting sort): a slab [k0, k1) visits only the buckets that can reach it, so no slab ever
// scans every triangle. With a single slab the sort is skipped: index order is as good.
struct SliceBuckets {
  std::vector<int32_t> k_first, k_last;  // per triangle, clamped to the grid; first > last = none
  std::vector<int64_t> start;            // nz + 1 (empty when not bucketed)
  std::vector<int32_t> order;
  int64_t max_span = 0;
};

SliceBuckets bucket_by_slice(const ScanProblem& p, bool sort, int threads) {
  const auto& tris = *p.triangles;
  SliceBuckets b;
  b.k_first.resize(tris.size());
  b.k_last.resize(tris.size());
  const double last_slice = double(p.nz - 1);
  std::atomic<int64_t> max_span_all{0};
  parallel_for(int64_t(tris.size()), threads, [&](int64_t t_begin, int64_t t_end) {
    int64_t max_span = 0;
    for (size_t t = size_t(t_begin); t < size_t(t_end); ++t) {
      const double z0 = p.z[size_t(tris[t][0])], z1 = p.z[size_t(tris[t][1])], z2 = p.z[size_t(tris[t][2])];
      const double lo = std::max(std::ceil(std::min({z0, z1, z2})), 0.0);
      const double hi = std::min(std::floor(std::max({z0, z1, z2})), last_slice);
      const bool any = lo <= hi;
      b.k_first[t] = any ? int32_t(lo) : 1;
      b.k_last[t] = any ? int32_t(hi) : 0;
      if (any) max_span = std::max<int64_t>(max_span, b.k_last[t] - b.k_first[t]);
    }
    for (int64_t seen = max_span_all.load(); seen < max_span && !max_span_all.compare_exchange_weak(seen, max_span);) {
    }
  });
  b.max_span = max_span_all.load();
  if (!sort) return b;
  b.start.assign(size_t(p.nz + 1), 0);
  for (size_t t = 0; t < tris.size(); ++t) {
    if (b.k_first[t] <= b.k_last[t]) ++b.start[size_t(b.k_first[t]) + 1];
  }
  for (int64_t k = 0; k < p.nz; ++k) b.start[size_t(k + 1)] += b.start[size_t(k)];
  b.order.resize(size_t(b.start[size_t(p.nz)]));
  std::vector<int64_t> fill(b.start.begin(), b.start.end() - 1);
  for (size_t t = 0; t < tris.size(); ++t) {
    if (b.k_first[t] <= b.k_last[t]) b.order[size_t(fill[size_t(b.k_first[t])]++)] = int32_t(t);
  }
  return b;
}

// Appends the crossings of triangle t with the row lines of slices [k_lo, k_hi].
void triangle_crossings(const ScanProblem& p, const std::array<int32_t, 3>& tri, int64_t k_lo, int64_t k_hi, int64_t k0,
                        std::vector<LineCrossingAt>& out) {
  const size_t a = size_t(tri[0]), b = size_t(tri[1]), c = size_t(tri[2]);
  const double ymin = std::min({p.y[a], p.y[b], p.y[c]}), ymax = std::max({p.y[a], p.y[b], p.y[c]});
  const int64_t j_lo = int64_t(std::max(std::ceil(ymin), 0.0));
  const int64_t j_hi = int64_t(std::min(std::floor(ymax), double(p.ny - 1)));
  if (j_lo > j_hi) return;
  const ProjectedEdge ab(p.y[a], p.z[a], p.y[b], p.z[b]);
  const ProjectedEdge bc(p.y[b], p.z[b], p.y[c], p.z[c]);
  const ProjectedEdge ca(p.y[c], p.z[c], p.y[a], p.z[a]);
  for (int64_t k = k_lo; k <= k_hi; ++k) {
    const double pz = double(k);
    for (int64_t j = j_lo; j <= j_hi; ++j) {
      const double py = double(j);
      const double w_c = ab.value(py, pz), w_a = bc.value(py, pz), w_b = ca.value(py, pz);
      const int s = ProjectedEdge::sign_of(w_c, ab.tie_sign);
      if (ProjectedEdge::sign_of(w_a, bc.tie_sign) != s || ProjectedEdge::sign_of(w_b, ca.tie_sign) != s) continue;
      // Barycentric interpolation with the edge functions as weights: two triangles sharing an
      // edge give the same x on it, and a line through a vertex gets exactly that vertex's x.
      const double x = (w_a * p.x[a] + w_b * p.x[b] + w_c * p.x[c]) / (w_a + w_b + w_c);
      // All weights positive: counter-clockwise in (y,z), normal along +x, so the line leaves.
      out.push_back({j + p.ny * (k - k0), {x, s > 0 ? -1 : 1}});
    }
  }
}

LineRuns scan_slab(const ScanProblem& p, const SliceBuckets& buckets, int64_t k0, int64_t k1, bool drop_unbalanced) {
  const auto& tris = *p.triangles;
  std::vector<LineCrossingAt> crossings;
  // Enough for a closed surface crossing each line it reaches a few times, so growth (a copy of
  // every crossing) is rare.
  crossings.reserve(size_t(std::max<int64_t>(4 * p.ny * (k1 - k0), int64_t(tris.size()) / 2)));
  auto visit = [&](size_t t) {
    if (buckets.k_last[t] < k0 || buckets.k_first[t] >= k1) return;
    triangle_crossings(p, tris[t], std::max<int64_t>(buckets.k_first[t], k0),
                       std::min<int64_t>(buckets.k_last[t], k1 - 1), k0, crossings);
  };
  if (buckets.start.empty()) {
    for (size_t t = 0; t < tris.size(); ++t) visit(t);
  } else {
    for (int64_t kb = std::max<int64_t>(0, k0 - buckets.max_span); kb < k1; ++kb) {
      for (int64_t o = buckets.start[size_t(kb)]; o < buckets.start[size_t(kb + 1)]; ++o) {
        visit(size_t(buckets.order[size_t(o)]));
      }
    }
  }
  return fill_lines(crossings, p.ny * (k1 - k0), p.nx, p.rule, drop_unbalanced);
}

// Scans every row line of the grid, slabs of slices in parallel, and concatenates the slabs in
// slice order, so the result does not depend on the thread count.
LineRuns scan(const ScanProblem& p, int threads, bool drop_unbalanced) {
  const int64_t slab_count = std::max<int64_t>(1, std::min<int64_t>(p.nz, threads <= 1 ? 1 : int64_t(threads) * 8));
  const SliceBuckets buckets = bucket_by_slice(p, slab_count > 1, threads);
  std::vector<LineRuns> slabs(static_cast<size_t>(slab_count));
  auto slab_k = [&](int64_t s) { return p.nz * s / slab_count; };
  std::atomic<int64_t> next{0};
  auto work = [&] {
    for (int64_t s; (s = next.fetch_add(1)) < slab_count;) {
      slabs[size_t(s)] = scan_slab(p, buckets, slab_k(s), slab_k(s + 1), drop_unbalanced);
    }
  };
  if (threads <= 1 || slab_count == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work);
    for (auto& t : pool) t.join();
  }
  LineRuns out;
  out.line_start.reserve(size_t(p.ny * p.nz + 1));
  size_t total_runs = 0;
  for (const auto& s : slabs) total_runs += s.runs.size();
  out.runs.reserve(total_runs);
  for (const auto& s : slabs) {
    const int64_t base = int64_t(out.runs.size());
    for (size_t l = 0; l + 1 < s.line_start.size(); ++l) out.line_start.push_back(base + s.line_start[l]);
    out.runs.insert(out.runs.end(), s.runs.begin(), s.runs.end());
    out.unbalanced_lines += s.unbalanced_lines;
  }
  out.line_start.push_back(int64_t(out.runs.size()));
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
