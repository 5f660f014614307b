#include "core/voxelize/memory_estimate.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <vector>

namespace soiq {
namespace {

constexpr int64_t kMax = std::numeric_limits<int64_t>::max();

// a * b + c, saturating: estimates of absurd inputs must stay comparable, never wrap.
int64_t mul_add(int64_t a, int64_t b, int64_t c = 0) {
  if (a <= 0 || b <= 0) return std::min(kMax, std::max<int64_t>(c, 0));
  if (a > (kMax - std::max<int64_t>(c, 0)) / b) return kMax;
  return a * b + c;
}

// dims[0] x dims[1] x dims[2], saturating (ImageGeometry::voxel_count() trusts its caller's checks).
int64_t voxels(const ImageGeometry& g) { return mul_add(mul_add(g.dims[0], g.dims[1]), g.dims[2]); }

int64_t saturating(double x) { return x >= 9.0e18 ? kMax : int64_t(std::max(0.0, x)); }

}  // namespace

SurfaceMeasure surface_measure(const TriangleMesh& mesh) {
  SurfaceMeasure m;
  m.vertices = int64_t(mesh.vertices_mm.size());
  m.triangles = int64_t(mesh.triangles.size());
  // L1 norms bound the Euclidean ones from above (by at most sqrt(3)) without square roots: this
  // pass must stay cheap beside the conversion it guards. Four partial sums break the dependency
  // chain of one accumulator.
  auto l1 = [](const Vec3& v) { return std::abs(v[0]) + std::abs(v[1]) + std::abs(v[2]); };
  double area[4] = {0, 0, 0, 0}, perimeter[4] = {0, 0, 0, 0};
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Vec3& a = mesh.vertices_mm[size_t(t[0])];
    const Vec3& b = mesh.vertices_mm[size_t(t[1])];
    const Vec3& c = mesh.vertices_mm[size_t(t[2])];
    const Vec3 ab = b - a, ac = c - a;
    area[i & 3] += 0.5 * l1(cross(ab, ac));
    perimeter[i & 3] += l1(ab) + l1(ac) + l1(c - b);
  }
  m.area_mm2 = (area[0] + area[1]) + (area[2] + area[3]);
  m.perimeter_mm = (perimeter[0] + perimeter[1]) + (perimeter[2] + perimeter[3]);
  return m;
}

namespace {

// The row lines' lattice seen along the rows: the area in mm2 one line stands for, and the
// shortest a lattice unit can be in mm, which bound the lines through a triangle by its area and
// perimeter. On a sheared grid the cell is the slices' distance high (not the k spacing) and
// leans: its shortest unit is at least its area over its diagonal.
struct LineLattice {
  double cell_mm2, unit_mm;
};

LineLattice line_lattice(const ImageGeometry& g) {
  const double sy = g.spacing_mm[1], sz = g.spacing_mm[2];
  if (!g.sheared() && !g.uneven()) return {sy * sz, std::min(sy, sz)};
  // Unevenly spaced slices: the closest pair bounds the density of lines.
  double closest = 1;
  const std::vector<double>& p = g.slice_positions_mm;
  for (size_t k = 1; k < p.size(); ++k) closest = std::min(closest, (p[k] - p[k - 1]) / sz);
  const double cell = sy * g.slice_distance_mm() * closest;
  return {cell, cell / std::sqrt(sy * sy + sz * sz)};
}

}  // namespace

ConversionEstimate conversion_peak_bytes(const SurfaceMeasure& surface, const ImageGeometry& geometry, bool robust) {
  ConversionEstimate e;
  e.lines = mul_add(geometry.dims[1], geometry.dims[2]);
  // The row lines through a triangle are the lattice points (j,k) inside its projection on the
  // (y,z) index plane: at most its projected area plus half its perimeter plus one (Pick). A
  // projection is no larger than the triangle, and index units are spacing_mm long, so the sum over
  // the surface is bounded by its area and perimeter alone, whatever the grid's orientation: one
  // measure per surface serves every grid (in double: absurd meshes exceed int64, saturating()
  // clamps).
  const LineLattice lattice = line_lattice(geometry);
  const double crossings =
      surface.area_mm2 / lattice.cell_mm2 + 0.5 * surface.perimeter_mm / lattice.unit_mm + double(surface.triangles);
  e.crossings = saturating(crossings);
  constexpr int64_t kPerLine = 4 * 24 + 3 * 8;  // reserved crossings, line starts (slab and result), sort counts
  const int64_t reserved = mul_add(e.lines, 4);
  const int64_t beyond = e.crossings > reserved ? e.crossings - reserved : 0;
  int64_t bytes = mul_add(e.lines, kPerLine);
  bytes = mul_add(beyond, 48, bytes);
  bytes = mul_add(e.crossings / 2 + 1, 16, bytes);  // runs, and their copy into the result
  bytes = mul_add(surface.vertices, 24, bytes);
  bytes = mul_add(surface.triangles, 32, bytes);
  if (robust) bytes = mul_add(voxels(geometry), 2, bytes);
  e.bytes = bytes;
  return e;
}

ConversionEstimate conversion_peak_bytes(const TriangleMesh& mesh, const ImageGeometry& geometry, bool robust) {
  return conversion_peak_bytes(surface_measure(mesh), geometry, robust);
}

namespace {

// The voxels within a voxel diagonal of the surface (coverage_peak_bytes explains the bound).
double touched_voxels(const SurfaceMeasure& surface, const ImageGeometry& geometry) {
  const double sx = geometry.spacing_mm[0], sy = geometry.spacing_mm[1], sz = geometry.spacing_mm[2];
  // A sheared voxel's longest diagonal is at most the sum of its edges.
  const double d = geometry.sheared() ? sx + sy + sz : std::sqrt(sx * sx + sy * sy + sz * sz);
  return (2 * d * surface.area_mm2 + M_PI * d * d * surface.perimeter_mm +
          4.0 / 3.0 * M_PI * d * d * d * double(surface.triangles)) /
         geometry.voxel_volume_mm3();
}

}  // namespace

int64_t covered_voxels_bound(const SurfaceMeasure& surface, const ImageGeometry& geometry) {
  const double inside = std::pow(surface.area_mm2, 1.5) / (6 * std::sqrt(M_PI)) / geometry.voxel_volume_mm3();
  return std::min(voxels(geometry), saturating(inside + touched_voxels(surface, geometry)));
}

ConversionEstimate coverage_peak_bytes(const SurfaceMeasure& surface, const ImageGeometry& geometry,
                                       int lines_per_voxel) {
  const double n = std::max(lines_per_voxel, 1);
  ConversionEstimate e;
  e.lines = mul_add(geometry.dims[1], geometry.dims[2]);
  const LineLattice lattice = line_lattice(geometry);
  e.crossings = saturating(n * n * surface.area_mm2 / lattice.cell_mm2 +
                           n * 0.5 * surface.perimeter_mm / lattice.unit_mm + double(surface.triangles));
  const int64_t partial = std::min(voxels(geometry), saturating(touched_voxels(surface, geometry)));
  const int64_t slice_lines = mul_add(geometry.dims[1], int64_t(n * n), 1);
  // Two threads' slices hold disjoint crossings: 24 bytes found (doubled by growth), 16 grouped.
  int64_t bytes = mul_add(e.crossings, 64);
  bytes = mul_add(slice_lines, 2 * 2 * 8, bytes);      // two threads' line starts, and the copies
  bytes = mul_add(e.crossings / 2 + 1, 2 * 8, bytes);  // full runs
  bytes = mul_add(partial, 2 * 8, bytes);
  bytes = mul_add(e.lines, 2 * 8, bytes);  // the result's two line indexes
  bytes = mul_add(surface.vertices, 24, bytes);
  // Per triangle its slice range, and its place in each voxel slice's list.
  const double sx = geometry.spacing_mm[0], sy = geometry.spacing_mm[1], sz = geometry.slice_distance_mm();
  bytes = mul_add(surface.triangles + saturating(surface.perimeter_mm / std::min(sx, std::min(sy, sz))), 12, bytes);
  bytes = mul_add(geometry.dims[2], 2 * 8 + 64, bytes);  // slice counts and per-slice results
  e.bytes = bytes;
  return e;
}

int64_t fraction_export_extra_bytes(const ImageGeometry& geometry, int bytes_per_voxel) {
  return mul_add(voxels(geometry), 2 * int64_t(std::max(bytes_per_voxel, 1)) + 1);
}

int64_t features_extra_bytes(const ConversionEstimate& conversion, const ImageGeometry& geometry,
                             int64_t uncached_image_voxels, int regions) {
  int64_t bytes = mul_add(conversion.crossings / 2 + 1, 64);
  bytes = mul_add(voxels(geometry), 1, bytes);  // measured ~0.5 byte per grid voxel (sweeps)
  bytes = mul_add(uncached_image_voxels, 4, bytes);
  if (regions > 0) bytes = mul_add(voxels(geometry), 4, bytes);
  return bytes;
}

int64_t mask_export_extra_bytes(const ImageGeometry& geometry) { return mul_add(voxels(geometry), 3); }

// "8589934592", "8G", "512M", "64K", "1T" (binary multiples; a trailing "B" or "iB" allowed).
Result<int64_t> parse_byte_size(const std::string& text, const std::string& what) {
  std::string digits = text;
  int64_t unit = 1;
  for (const std::string& tail : {std::string("iB"), std::string("B")}) {
    if (digits.size() > tail.size() && digits.ends_with(tail)) digits.resize(digits.size() - tail.size());
  }
  if (!digits.empty()) {
    const char last = char(std::toupper(static_cast<unsigned char>(digits.back())));
    const std::string units = "KMGT";
    if (const size_t at = units.find(last); at != std::string::npos) {
      unit = int64_t(1) << (10 * (at + 1));
      digits.pop_back();
    }
  }
  int64_t n = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || n < 1 ||
      n > (int64_t(1) << 50) / unit) {
    return invalid_argument(what + " must be a size in bytes such as 8G, 512M or 1073741824, not '" +
                            text.substr(0, 40) + "'");
  }
  return n * unit;
}

namespace {

// What is left of a process limit (RLIMIT_AS, RLIMIT_DATA) over what the process already uses
// there, less `headroom`; INT64_MAX when the limit is unlimited.
int64_t rlimit_left(int resource, int64_t in_use, int64_t headroom) {
  rlimit r{};
  if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return INT64_MAX;
  const int64_t limit = r.rlim_cur > rlim_t(INT64_MAX) ? INT64_MAX : int64_t(r.rlim_cur);
  return std::max<int64_t>(0, limit - in_use - headroom);
}

}  // namespace

int64_t default_memory_budget_bytes() {
  int64_t total = int64_t(sysconf(_SC_PHYS_PAGES)) * int64_t(sysconf(_SC_PAGE_SIZE));
  // cgroup v2: a container's limit, "max" when there is none.
  std::ifstream cgroup("/sys/fs/cgroup/memory.max");
  std::string text;
  if (cgroup >> text && text != "max") {
    try {
      const int64_t limit = std::stoll(text);
      if (limit > 0 && (total <= 0 || limit < total)) total = limit;
    } catch (...) {
    }
  }
  if (total <= 0) total = int64_t(4) << 30;
  // The process's own limits (ulimit -v, -d): what is left of them now, less what a server's
  // threads will map later (a stack and a malloc arena's reserve each, ~72 MiB of address space
  // for each of some 16 threads). Work admitted past them would fail to allocate instead of
  // queueing.
  const int64_t page = int64_t(sysconf(_SC_PAGE_SIZE));
  int64_t vm_pages = 0, resident = 0, shared = 0, text_pages = 0, lib = 0, data_pages = 0;
  std::ifstream statm("/proc/self/statm");
  statm >> vm_pages >> resident >> shared >> text_pages >> lib >> data_pages;
  constexpr int64_t kThreadsHeadroom = int64_t(1152) << 20;
  total = std::min(total, rlimit_left(RLIMIT_AS, vm_pages * page, kThreadsHeadroom));
  total = std::min(total, rlimit_left(RLIMIT_DATA, data_pages * page, kThreadsHeadroom));
  return std::max<int64_t>(total / 2, int64_t(64) << 20);
}

std::string human_bytes(int64_t bytes) {
  const char* units[] = {"bytes", "KB", "MB", "GB", "TB", "PB", "EB"};
  double v = double(bytes);
  int u = 0;
  while (v >= 1000 && u < 6) {
    v /= 1000;
    ++u;
  }
  char text[32];
  if (u == 0) {
    std::snprintf(text, sizeof text, "%lld bytes", static_cast<long long>(bytes));
  } else {
    std::snprintf(text, sizeof text, v >= 100 ? "%.0f %s" : v >= 10 ? "%.1f %s" : "%.2f %s", v, units[u]);
  }
  return text;
}

}  // namespace soiq
