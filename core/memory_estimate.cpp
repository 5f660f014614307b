#include "core/memory_estimate.h"

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

int64_t saturating(double x) { return x >= 9.0e18 ? kMax : int64_t(std::max(0.0, x)); }

}  // namespace

ConversionEstimate conversion_peak_bytes(const TriangleMesh& mesh, const ImageGeometry& geometry, bool robust) {
  ConversionEstimate e;
  e.lines = mul_add(geometry.dims[1], geometry.dims[2]);
  // Lattice points (j,k) inside each triangle's (y,z) projection in index space, summed in double
  // (it can exceed int64 for absurd meshes; saturating() clamps).
  double crossings = 0;
  std::vector<Vec3> index(mesh.vertices_mm.size());
  for (size_t v = 0; v < index.size(); ++v) index[v] = geometry.physical_to_index(mesh.vertices_mm[v]);
  for (const auto& t : mesh.triangles) {
    const Vec3& a = index[size_t(t[0])];
    const Vec3& b = index[size_t(t[1])];
    const Vec3& c = index[size_t(t[2])];
    const double area = 0.5 * std::abs((b[1] - a[1]) * (c[2] - a[2]) - (c[1] - a[1]) * (b[2] - a[2]));
    const double perimeter = std::hypot(b[1] - a[1], b[2] - a[2]) + std::hypot(c[1] - b[1], c[2] - b[2]) +
                             std::hypot(a[1] - c[1], a[2] - c[2]);
    crossings += area + 0.5 * perimeter + 1;
  }
  e.crossings = saturating(crossings);
  constexpr int64_t kPerLine = 4 * 24 + 3 * 8;  // reserved crossings, line starts (slab and result), sort counts
  const int64_t reserved = mul_add(e.lines, 4);
  const int64_t beyond = e.crossings > reserved ? e.crossings - reserved : 0;
  int64_t bytes = mul_add(e.lines, kPerLine);
  bytes = mul_add(beyond, 48, bytes);
  bytes = mul_add(e.crossings / 2 + 1, 16, bytes);  // runs, and their copy into the result
  bytes = mul_add(int64_t(mesh.vertices_mm.size()), 24, bytes);
  bytes = mul_add(int64_t(mesh.triangles.size()), 32, bytes);
  if (robust) bytes = mul_add(geometry.voxel_count(), 2, bytes);
  e.bytes = bytes;
  return e;
}

int64_t features_extra_bytes(const ConversionEstimate& conversion, const ImageGeometry& geometry,
                             int64_t uncached_image_voxels, int regions) {
  int64_t bytes = mul_add(conversion.crossings / 2 + 1, 64);
  bytes = mul_add(geometry.voxel_count(), 1, bytes);  // measured ~0.5 byte per grid voxel (sweeps)
  bytes = mul_add(uncached_image_voxels, 4, bytes);
  if (regions > 0) bytes = mul_add(geometry.voxel_count(), 4, bytes);
  return bytes;
}

int64_t mask_export_extra_bytes(const ImageGeometry& geometry) { return mul_add(geometry.voxel_count(), 3); }

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
  return total / 2;
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
