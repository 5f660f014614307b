#include "core/base/image_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/base/physical_to_lattice.h"

namespace soiq {

Vec3 ImageGeometry::lattice_to_physical(const Vec3& ijz) const {
  const Vec3 scaled{ijz[0] * spacing_mm[0], ijz[1] * spacing_mm[1], ijz[2] * spacing_mm[2]};
  return origin_mm + mul(direction, scaled);
}

Vec3 ImageGeometry::index_to_physical(const Vec3& ijk) const {
  if (!uneven()) return lattice_to_physical(ijk);
  return lattice_to_physical({ijk[0], ijk[1], lattice_z(ijk[2])});
}

double ImageGeometry::lattice_z(double k) const {
  if (!uneven()) return k;
  const std::vector<double>& p = slice_positions_mm;
  const size_t n = p.size();
  if (n < 2) return k;  // not a valid uneven grid (validate_geometry): no pieces to follow
  // The piece holding k: [a, a + 1], the end pieces extended.
  const double a = std::clamp(std::floor(k), 0.0, double(n - 2));
  const size_t i = size_t(a);
  return (p[i] + (k - a) * (p[i + 1] - p[i])) / spacing_mm[2];
}

double ImageGeometry::slice_index(double z) const {
  if (!uneven()) return z;
  const std::vector<double>& p = slice_positions_mm;
  if (p.size() < 2) return z;
  const double mm = z * spacing_mm[2];
  // The piece [p[i], p[i + 1]] holding mm, the end pieces extended.
  const size_t upper = size_t(std::upper_bound(p.begin(), p.end(), mm) - p.begin());
  const size_t i = std::min(std::max<size_t>(upper, 1), p.size() - 1) - 1;
  return double(i) + (mm - p[i]) / (p[i + 1] - p[i]);
}

double ImageGeometry::voxel_volume_mm3(int64_t k) const {
  if (!uneven()) return voxel_volume_mm3();
  const std::vector<double>& p = slice_positions_mm;
  if (p.size() < 2) return voxel_volume_mm3();
  const size_t n = p.size(), i = size_t(std::clamp<int64_t>(k, 0, int64_t(n - 1)));
  const double below = i > 0 ? p[i] - p[i - 1] : p[1] - p[0];
  const double above = i + 1 < n ? p[i + 1] - p[i] : p[n - 1] - p[n - 2];
  return voxel_volume_mm3() / spacing_mm[2] * 0.5 * (below + above);
}

namespace {

Vec3 column(const Mat3& m, int c) { return {m[0][c], m[1][c], m[2][c]}; }

constexpr double kOrthonormalTolerance = 1e-4;

}  // namespace

bool ImageGeometry::sheared() const {
  const Vec3 k = column(direction, 2);
  return std::abs(dot(k, column(direction, 0))) > kOrthonormalTolerance ||
         std::abs(dot(k, column(direction, 1))) > kOrthonormalTolerance;
}

double ImageGeometry::slice_distance_mm() const {
  if (!sheared()) return spacing_mm[2];
  const Vec3 n = cross(column(direction, 0), column(direction, 1));
  return spacing_mm[2] * std::abs(dot(column(direction, 2), n));
}

double ImageGeometry::voxel_volume_mm3() const {
  if (!sheared()) return spacing_mm[0] * spacing_mm[1] * spacing_mm[2];
  return spacing_mm[0] * spacing_mm[1] * slice_distance_mm();
}

Mat3 ImageGeometry::frame() const {
  if (!sheared()) return direction;
  const Vec3 n = cross(column(direction, 0), column(direction, 1));
  const double side = dot(column(direction, 2), n) < 0 ? -1.0 : 1.0;
  Mat3 f = direction;
  for (int r = 0; r < 3; ++r) f[r][2] = side * n[r];
  return f;
}

double ImageGeometry::tilt_degrees() const {
  if (!sheared()) return 0;
  const Vec3 n = cross(column(direction, 0), column(direction, 1));
  const double c = std::min(1.0, std::abs(dot(column(direction, 2), n)) / norm(n));
  return std::acos(c) * 180 / std::numbers::pi;
}

Vec3 ImageGeometry::physical_to_index(const Vec3& p_mm) const {
  if (!uneven()) return physical_to_lattice(p_mm);
  const Vec3 l = physical_to_lattice(p_mm);
  return {l[0], l[1], slice_index(l[2])};
}

Vec3 ImageGeometry::physical_to_lattice(const Vec3& p_mm) const { return PhysicalToLattice(*this)(p_mm); }

Status validate_geometry(const ImageGeometry& g) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(g.origin_mm[a])) return invalid_argument("grid origin is not finite");
    if (!(g.spacing_mm[a] > 0) || !std::isfinite(g.spacing_mm[a])) {
      return invalid_argument("grid spacing must be finite and > 0, got " + std::to_string(g.spacing_mm[a]) +
                              " mm along axis " + std::to_string(a));
    }
    if (g.dims[a] < 0) return invalid_argument("grid dimensions must be >= 0");
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(g.direction[r][c])) return invalid_argument("grid direction matrix is not finite");
    }
  }
  // i and j orthonormal, k of unit length; k perpendicular to both unless the grid is sheared.
  const bool sheared = g.sheared();
  for (int a = 0; a < 3; ++a) {
    for (int b = a; b < 3; ++b) {
      if (sheared && a != b && b == 2) continue;
      const double d = dot(column(g.direction, a), column(g.direction, b));
      if (std::abs(d - (a == b ? 1.0 : 0.0)) > kOrthonormalTolerance) {
        return invalid_argument("grid direction matrix is not orthonormal (columns " + std::to_string(a) + " and " +
                                std::to_string(b) + " have dot product " + std::to_string(d) + ")");
      }
    }
  }
  if (g.uneven()) {
    const std::vector<double>& p = g.slice_positions_mm;
    if (int64_t(p.size()) != g.dims[2] || p.size() < 3) {
      return invalid_argument("grid has " + std::to_string(p.size()) + " slice positions for " +
                              std::to_string(g.dims[2]) +
                              " slices (an unevenly spaced grid needs one per slice, 3 or more)");
    }
    if (p[0] != 0) return invalid_argument("grid's first slice position is not 0");
    for (size_t k = 1; k < p.size(); ++k) {
      if (!std::isfinite(p[k]) || !(p[k] > p[k - 1])) {
        return invalid_argument("grid's slice positions must be finite and increasing: slice " + std::to_string(k) +
                                " at " + std::to_string(p[k]) + " mm after " + std::to_string(p[k - 1]));
      }
    }
    const double mean = p.back() / double(p.size() - 1);
    if (std::abs(mean - g.spacing_mm[2]) > 1e-9 * mean) {
      return invalid_argument("grid's k spacing " + std::to_string(g.spacing_mm[2]) +
                              " mm is not the mean step of its slice positions, " + std::to_string(mean));
    }
  }
  if (sheared && g.tilt_degrees() > kMaxTiltDegrees) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "grid slices are stacked %.1f degrees away from the normal of their planes; at most %g (gantry tilt) "
                  "is a slice stack",
                  g.tilt_degrees(), kMaxTiltDegrees);
    return invalid_argument(buf);
  }
  return ok_status();
}

Status check_grid_size(const ImageGeometry& g, int64_t max_voxels) {
  // Multiply in double first: three int64 dims can overflow int64.
  const double n = double(g.dims[0]) * double(g.dims[1]) * double(g.dims[2]);
  if (n > double(max_voxels)) {
    char buf[256];
    std::snprintf(
        buf, sizeof buf,
        "grid of %.3g voxels (%s) exceeds the limit of %.3g voxels; use a coarser spacing or a smaller region", n,
        describe(g).c_str(), double(max_voxels));
    return resource_exhausted(buf);
  }
  return ok_status();
}

Status check_same_grid(const ImageGeometry& a, const ImageGeometry& b) {
  if (a.dims != b.dims) return invalid_argument("grids differ in size: " + describe(a) + " vs " + describe(b));
  if (a.uneven() != b.uneven()) return invalid_argument("grids differ: " + describe(a) + " vs " + describe(b));
  for (size_t k = 0; k < a.slice_positions_mm.size(); ++k) {
    if (std::abs(a.slice_positions_mm[k] - b.slice_positions_mm[k]) > 1e-4) {
      return invalid_argument("grids differ in the position of slice " + std::to_string(k) + " by " +
                              std::to_string(std::abs(a.slice_positions_mm[k] - b.slice_positions_mm[k])) + " mm");
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (std::abs(a.spacing_mm[i] - b.spacing_mm[i]) > 1e-6 * std::max(a.spacing_mm[i], b.spacing_mm[i])) {
      return invalid_argument("grids differ in spacing: " + describe(a) + " vs " + describe(b));
    }
    if (std::abs(a.origin_mm[i] - b.origin_mm[i]) > 1e-4) {
      return invalid_argument("grids differ in origin by " + std::to_string(norm(a.origin_mm - b.origin_mm)) + " mm");
    }
    for (int j = 0; j < 3; ++j) {
      if (std::abs(a.direction[i][j] - b.direction[i][j]) > 1e-5) {
        return invalid_argument("grids differ in orientation (direction matrices)");
      }
    }
  }
  return ok_status();
}

ImageGeometry sub_grid(const ImageGeometry& g, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& dims) {
  ImageGeometry out = g;
  out.origin_mm = g.index_to_physical({double(lo[0]), double(lo[1]), double(lo[2])});
  out.dims = dims;
  if (!g.uneven()) return out;
  out.slice_positions_mm.clear();
  const std::vector<double>& p = g.slice_positions_mm;
  const size_t first = size_t(std::clamp<int64_t>(lo[2], 0, int64_t(p.size()) - 1));
  const size_t n = size_t(std::max<int64_t>(dims[2], 0));
  if (n >= 3 && first + n <= p.size()) {
    for (size_t k = 0; k < n; ++k) out.slice_positions_mm.push_back(p[first + k] - p[first]);
    out.slice_positions_mm[0] = 0;
    out.spacing_mm[2] = out.slice_positions_mm.back() / double(n - 1);
  } else if (n == 2 && first + 1 < p.size()) {
    out.spacing_mm[2] = p[first + 1] - p[first];
  }
  return out;
}

std::string describe(const ImageGeometry& g) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%lldx%lldx%lld voxels of %gx%gx%g mm", (long long)g.dims[0], (long long)g.dims[1],
                (long long)g.dims[2], g.spacing_mm[0], g.spacing_mm[1], g.spacing_mm[2]);
  std::string out = buf;
  if (g.uneven()) {
    double least = HUGE_VAL, most = 0;
    const std::vector<double>& p = g.slice_positions_mm;
    for (size_t k = 1; k < p.size(); ++k)
      least = std::min(least, p[k] - p[k - 1]), most = std::max(most, p[k] - p[k - 1]);
    const double along_normal = g.slice_distance_mm() / g.spacing_mm[2];
    char uneven[96];
    std::snprintf(uneven, sizeof uneven, ", unevenly spaced slices %g to %g mm apart", least * along_normal,
                  most * along_normal);
    out += uneven;
  }
  if (!g.sheared()) return out;
  char tilt[80];
  if (g.uneven()) {
    std::snprintf(tilt, sizeof tilt, ", tilted %.2g degrees", g.tilt_degrees());
  } else {
    std::snprintf(tilt, sizeof tilt, ", slices %g mm apart, tilted %.2g degrees", g.slice_distance_mm(),
                  g.tilt_degrees());
  }
  return out + tilt;
}

}  // namespace soiq
