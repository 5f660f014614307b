#include "core/voxelize/scan_lattice.h"

#include <algorithm>
#include <string>

#include "core/base/parallel_for.h"
#include "core/base/run_tasks.h"

namespace soiq::scanline {

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
      double lo = std::max(std::ceil(std::min({z0, z1, z2})), 0.0);
      double hi = std::min(std::floor(std::max({z0, z1, z2})), last_slice);
      if (!p.slice_z.empty()) {
        // The slices whose planes the triangle's z range holds, ends included.
        const auto& sz = p.slice_z;
        lo = double(std::lower_bound(sz.begin(), sz.end(), std::min({z0, z1, z2})) - sz.begin());
        hi = double(std::upper_bound(sz.begin(), sz.end(), std::max({z0, z1, z2})) - sz.begin()) - 1;
      }
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

ScanProblem index_space_problem(const TriangleMesh& mesh, const ImageGeometry& g, int axis, FillRule rule, int threads,
                                int lines_per_voxel) {
  ScanProblem p;
  const size_t n = mesh.vertices_mm.size();
  p.x.resize(n);
  p.y.resize(n);
  p.z.resize(n);
  parallel_for(int64_t(n), threads, [&](int64_t begin, int64_t end) {
    for (size_t v = size_t(begin); v < size_t(end); ++v) {
      const Vec3 u = g.physical_to_lattice(mesh.vertices_mm[v]);
      p.x[v] = u[size_t(axis)];
      p.y[v] = u[size_t((axis + 1) % 3)];
      p.z[v] = u[size_t((axis + 2) % 3)];
    }
    // n y + (n - 1)/2 puts line a of voxel j (at j - 1/2 + (a + 1/2)/n) on the integer n j + a.
    // One line per voxel keeps the coordinates untouched, so the 1D method stays exact.
    if (lines_per_voxel > 1) {
      const double n = lines_per_voxel, shift = (n - 1) / 2;
      for (size_t v = size_t(begin); v < size_t(end); ++v) {
        p.y[v] = n * p.y[v] + shift;
        p.z[v] = n * p.z[v] + shift;
      }
    }
  });
  p.triangles = &mesh.triangles;
  p.nx = g.dims[size_t(axis)];
  p.ny = g.dims[size_t((axis + 1) % 3)] * lines_per_voxel;
  p.nz = g.dims[size_t((axis + 2) % 3)] * lines_per_voxel;
  p.rule = rule;
  if (g.uneven() && axis == 0 && lines_per_voxel == 1) {
    p.slice_z.resize(size_t(g.dims[2]));
    for (int64_t k = 0; k < g.dims[2]; ++k) p.slice_z[size_t(k)] = g.lattice_z(double(k));
  }
  return p;
}

Status scan_supported(const ImageGeometry& g, int axis, int lines_per_voxel, const char* what) {
  if (!g.uneven() || (axis == 0 && lines_per_voxel == 1)) return ok_status();
  return failed_precondition(std::string(what) + " is not available on an unevenly spaced series (" + describe(g) +
                             "): its rows are not evenly spaced along k; the plain conversion is, or a grid of "
                             "your own (--spacing)");
}

}  // namespace soiq::scanline
