#include "core/voxelize/scan_lattice.h"

#include <algorithm>
#include <string>

#include "core/base/cpu_dispatch.h"
#include "core/base/parallel_for.h"
#include "core/base/physical_to_lattice.h"
#include "core/base/run_tasks.h"

namespace soiq::scanline {

namespace {

// Vertices [begin, end) of `mesh` into p's index space: the scan axis to x, the next two to y and z.
// n y + (n - 1)/2 puts line a of voxel j (at j - 1/2 + (a + 1/2)/n) on the integer n j + a. One
// line per voxel keeps the coordinates untouched, so the 1D method stays exact.
void map_vertices(const TriangleMesh& mesh, const PhysicalToLattice& to_lattice, int axis, int lines_per_voxel,
                  size_t begin, size_t end, ScanProblem& p) {
  const size_t ax = size_t(axis), ay = size_t((axis + 1) % 3), az = size_t((axis + 2) % 3);
  for (size_t v = begin; v < end; ++v) {
    const Vec3 u = to_lattice(mesh.vertices_mm[v]);
    p.xyz[v] = {u[ax], u[ay], u[az]};
  }
  if (lines_per_voxel > 1) {
    const double n = lines_per_voxel, shift = (n - 1) / 2;
    for (size_t v = begin; v < end; ++v) {
      p.xyz[v][1] = n * p.xyz[v][1] + shift;
      p.xyz[v][2] = n * p.xyz[v][2] + shift;
    }
  }
}

}  // namespace

SlabTriangles triangles_by_slab(const ScanProblem& p, const Slabs& slabs, int threads) {
  SlabTriangles b;
  const int64_t nslabs = slabs.count;
  if (nslabs <= 1) return b;
  const auto& tris = *p.triangles;
  const size_t n = tris.size();
  const int64_t chunks = std::max(threads, 1);
  // count[c * nslabs + s]: triangles of chunk c reaching slab s; then their first place in `order`.
  std::vector<int64_t> count(size_t(chunks * nslabs), 0);
  // Slab of each slice, looked up: a 64-bit division per triangle end cost more than the counting.
  std::vector<int32_t> slab_of(size_t(p.nz));
  for (int64_t k = 0; k < p.nz; ++k) slab_of[size_t(k)] = int32_t(slabs.of_slice(k));
  // The slabs a triangle reaches: [first, last], first > last when none.
  auto slabs_of = [&](size_t t) {
    const SliceRange r =
        slice_range(p, p.xyz[size_t(tris[t][0])][2], p.xyz[size_t(tris[t][1])][2], p.xyz[size_t(tris[t][2])][2]);
    if (r.first > r.last) return std::pair<int32_t, int32_t>(1, 0);
    return std::pair<int32_t, int32_t>(slab_of[size_t(r.first)], slab_of[size_t(r.last)]);
  };
  auto chunk_range = [&](int64_t c) {
    return std::pair<size_t, size_t>(n * size_t(c) / size_t(chunks), n * size_t(c + 1) / size_t(chunks));
  };
  run_tasks(chunks, int(chunks), [&](int64_t c) {
    cpu_dispatch([&] {
      const auto [begin, end] = chunk_range(c);
      // Counted locally and stored once: neighbouring chunks' counts share cache lines.
      std::vector<int64_t> mine(size_t(nslabs), 0);
      for (size_t t = begin; t < end; ++t) {
        const auto [first, last] = slabs_of(t);
        for (int32_t s = first; s <= last; ++s) ++mine[size_t(s)];
      }
      std::copy(mine.begin(), mine.end(), count.begin() + c * nslabs);
    });
  });
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
    cpu_dispatch([&] {
      const auto [begin, end] = chunk_range(c);
      std::vector<int64_t> next(count.begin() + c * nslabs, count.begin() + (c + 1) * nslabs);
      for (size_t t = begin; t < end; ++t) {
        const auto [first, last] = slabs_of(t);
        for (int32_t s = first; s <= last; ++s) b.order[size_t(next[size_t(s)]++)] = int32_t(t);
      }
    });
  });
  return b;
}

ScanProblem index_space_problem(const TriangleMesh& mesh, const ImageGeometry& g, int axis, FillRule rule, int threads,
                                int lines_per_voxel) {
  ScanProblem p;
  const size_t n = mesh.vertices_mm.size();
  p.xyz.resize(n);
  const PhysicalToLattice to_lattice(g);
  parallel_for(int64_t(n), threads, [&](int64_t begin, int64_t end) {
    cpu_dispatch([&] { map_vertices(mesh, to_lattice, axis, lines_per_voxel, size_t(begin), size_t(end), p); });
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
