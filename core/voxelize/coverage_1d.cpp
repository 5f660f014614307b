#include "core/voxelize/coverage_1d.h"

#include <algorithm>

#include "core/base/cpu_dispatch.h"
#include "core/base/run_tasks.h"
#include "core/voxelize/coverage_line.h"
#include "core/voxelize/scan_lattice.h"

namespace soiq {

namespace coverage_1d_detail {

struct SampleCrossingAt {
  int64_t line;  // sample line of the slice: j' + ny' * b, b the sample row within the voxel slice
  SampleCrossing crossing;
};

// One voxel slice's rows (j = 0..ny-1) of the coverage volume.
struct SliceCoverage {
  std::vector<int64_t> full_start, partial_start;  // ny entries each: where row j starts
  std::vector<Run> full;
  std::vector<PartialVoxel> partial;
  int64_t unbalanced_lines = 0;
};

// Scans the n sample slices of voxel slice k and reduces their n x n sample lines per voxel row.
SliceCoverage cover_slice(const scanline::ScanProblem& p, const scanline::SlabTriangles& by_slice, int64_t k, int n) {
  const int64_t ny = p.ny / n, k0 = k * n, k1 = k0 + n;
  thread_local std::vector<SampleCrossingAt> crossings;
  crossings.clear();
  by_slice.for_each_in_slab(k, p.triangles->size(), [&](size_t t) {
    scanline::for_each_hit(p, (*p.triangles)[t], k0, k1 - 1, [&](const scanline::LineHit& h) {
      crossings.push_back({h.j + p.ny * (h.k - k0), {h.x, h.normal_x_sign > 0 ? -1 : 1}});
    });
  });
  // Group by sample line (a counting sort).
  const int64_t lines = p.ny * n;
  thread_local std::vector<int64_t> start;
  thread_local std::vector<SampleCrossing> grouped;
  start.assign(size_t(lines + 1), 0);
  for (const SampleCrossingAt& c : crossings) ++start[size_t(c.line + 1)];
  for (int64_t l = 0; l < lines; ++l) start[size_t(l + 1)] += start[size_t(l)];
  grouped.resize(crossings.size());
  {
    thread_local std::vector<int64_t> next;
    next.assign(start.begin(), start.end() - 1);
    for (const SampleCrossingAt& c : crossings) grouped[size_t(next[size_t(c.line)]++)] = c.crossing;
  }
  SliceCoverage out;
  out.full_start.resize(size_t(ny));
  out.partial_start.resize(size_t(ny));
  thread_local std::vector<CoverageEvent> events;
  for (int64_t j = 0; j < ny; ++j) {
    out.full_start[size_t(j)] = int64_t(out.full.size());
    out.partial_start[size_t(j)] = int64_t(out.partial.size());
    events.clear();
    for (int64_t b = 0; b < n; ++b) {
      for (int64_t a = 0; a < n; ++a) {
        const int64_t l = (j * n + a) + p.ny * b;
        SampleCrossing* first = grouped.data() + start[size_t(l)];
        SampleCrossing* last = grouped.data() + start[size_t(l + 1)];
        if (first != last && !sample_line_events(first, last, p.rule, events)) ++out.unbalanced_lines;
      }
    }
    if (!events.empty()) cover_line(events, p.nx, n * n, out.full_start[size_t(j)], out.full, out.partial);
  }
  // The buffers stay with the thread for the next slice, but not past a large one: memory the
  // admission counted for this conversion must not stay held after it.
  constexpr size_t kKeptCrossings = size_t(1) << 20;
  if (crossings.capacity() > kKeptCrossings) std::vector<SampleCrossingAt>().swap(crossings);
  if (grouped.capacity() > kKeptCrossings) std::vector<SampleCrossing>().swap(grouped);
  return out;
}

}  // namespace coverage_1d_detail

Result<CoverageVolume> coverage_1d(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                   const CoverageOptions& options) {
  const std::string name = options.name ? options.name : "mesh";
  const int n = options.lines_per_voxel;
  if (n < 1 || n > kMaxLinesPerVoxel) {
    return invalid_argument("oversampling must be 1 to " + std::to_string(kMaxLinesPerVoxel) +
                            " lines per voxel side, not " + std::to_string(n));
  }
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  SOIQ_RETURN_IF_ERROR(scanline::scan_supported(geometry, 0, 2, "coverage fractions"));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, options.max_voxels));
  if (geometry.dims[0] > INT32_MAX - 2) return invalid_argument("grid rows longer than 2^31 voxels are not supported");
  if (geometry.dims[1] * n > INT32_MAX || geometry.dims[2] * n > INT32_MAX) {
    return resource_exhausted("grid " + describe(geometry) + " has too many sample lines at " + std::to_string(n) +
                              " per voxel side");
  }
  const MeshDefects defects = options.known_defects ? *options.known_defects : mesh_defects(mesh);
  SOIQ_RETURN_IF_ERROR(validate_mesh(mesh, defects, name));
  if (!defects.closed()) {
    return failed_precondition("mesh '" + name + "' is not closed and consistently oriented (" + describe(defects) +
                               "); coverage fractions need a closed surface: repair the mesh");
  }
  CoverageVolume out;
  out.geometry = geometry;
  out.lines_per_voxel = n;
  const int64_t ny = geometry.dims[1], nz = geometry.dims[2], lines = ny * nz;
  out.full_start.assign(size_t(lines + 1), 0);
  out.partial_start.assign(size_t(lines + 1), 0);
  if (geometry.voxel_count() == 0) return out;

  const int threads = std::max(1, options.threads);
  const scanline::ScanProblem p = scanline::index_space_problem(mesh, geometry, 0, options.fill_rule, threads, n);
  // One slab per voxel slice, whatever the thread count: the crossings of n^2 times the lines are
  // only ever held for one slice at a time.
  scanline::Slabs slabs;
  slabs.nz = p.nz;
  slabs.count = nz;
  const scanline::SlabTriangles by_slice = scanline::triangles_by_slab(p, slabs, threads);
  std::vector<coverage_1d_detail::SliceCoverage> slices{size_t(nz)};
  run_tasks(nz, threads, [&](int64_t k) {
    slices[size_t(k)] = cpu_dispatch([&] { return coverage_1d_detail::cover_slice(p, by_slice, k, n); });
  });

  // Concatenate in slice order (serially: it copies only the output, O(runs + partial voxels)).
  int64_t unbalanced = 0;
  for (int64_t k = 0; k < nz; ++k) {
    coverage_1d_detail::SliceCoverage& s = slices[size_t(k)];
    unbalanced += s.unbalanced_lines;
    const int64_t full_base = int64_t(out.full.size()), partial_base = int64_t(out.partial.size());
    for (int64_t j = 0; j < ny; ++j) {
      out.full_start[size_t(j + ny * k)] = full_base + s.full_start[size_t(j)];
      out.partial_start[size_t(j + ny * k)] = partial_base + s.partial_start[size_t(j)];
    }
    out.full.insert(out.full.end(), s.full.begin(), s.full.end());
    out.partial.insert(out.partial.end(), s.partial.begin(), s.partial.end());
    s = {};
  }
  out.full_start[size_t(lines)] = int64_t(out.full.size());
  out.partial_start[size_t(lines)] = int64_t(out.partial.size());
  if (unbalanced > 0) {
    return internal_error("mesh '" + name + "' passed the closedness check but " + std::to_string(unbalanced) +
                          " sample lines cross it an unbalanced number of times; please report this mesh");
  }
  return out;
}

}  // namespace soiq
