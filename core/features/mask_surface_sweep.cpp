#include "core/features/mask_surface_sweep.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "core/base/cpu_dispatch.h"

namespace soiq {
namespace {

constexpr int32_t kNone = std::numeric_limits<int32_t>::max();

Status check_volume(const RunLengthVolume& v) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(v.geometry));
  const std::string bad = "volume's run table does not match its grid (" + describe(v.geometry) + ")";
  if (int64_t(v.line_start.size()) != v.line_count() + 1 || v.line_start.back() != int64_t(v.runs.size())) {
    return invalid_argument(bad);
  }
  for (const Run& run : v.runs) {
    if (run.begin < 0 || run.begin >= run.end || run.end > v.geometry.dims[0]) return invalid_argument(bad);
  }
  return ok_status();
}

// A family's tables over the doubled bounding box [2 lo - 1, 2 hi + 1] of every axis.
PlaneFamily make_family(int axis, int row_axis, int value_axis, const std::array<int64_t, 3>& lo,
                        const std::array<int64_t, 3>& hi) {
  PlaneFamily f;
  f.axis = axis, f.row_axis = row_axis, f.value_axis = value_axis;
  f.plane_base = 2 * lo[size_t(axis)] - 1;
  f.row_base = 2 * lo[size_t(row_axis)] - 1;
  f.planes = 2 * (hi[size_t(axis)] - lo[size_t(axis)]) + 3;
  f.rows = 2 * (hi[size_t(row_axis)] - lo[size_t(row_axis)]) + 3;
  f.min.assign(size_t(f.planes * f.rows), kNone);
  f.max.assign(size_t(f.planes * f.rows), -kNone);
  return f;
}

class Sweep {
 public:
  Sweep(const RunLengthVolume& v, MaskSurfaceSweep& out) : v_(v), out_(out) {}

  // One vertex at doubled coordinates (x, y, z) into the three families.
  void vertex(int64_t x, int64_t y, int64_t z) {
    add(out_.families[0], x, z, y);
    add(out_.families[1], y, z, x);
    add(out_.families[2], z, y, x);
  }
  // The vertices (2 i, y, z) for i in [a, c): the X-valued families need only the two ends.
  void vertex_row(int64_t a, int64_t c, int64_t y, int64_t z) {
    for (const int64_t x : {2 * a, 2 * (c - 1)}) {
      add(out_.families[1], y, z, x);
      add(out_.families[2], z, y, x);
    }
    for (int64_t i = a; i < c; ++i) add(out_.families[0], 2 * i, z, y);
  }

  // The cubes whose lowest corner is (i, j, k) for every i, and the vertices on their lines.
  void quad(int64_t j, int64_t k) {
    const auto& d = v_.geometry.dims;
    events_.clear();
    for (int b = 0; b < 4; ++b) {
      const int64_t jj = j + (b & 1), kk = k + (b >> 1);
      if (jj < 0 || jj >= d[1] || kk < 0 || kk >= d[2]) continue;
      const int64_t l = jj + d[1] * kk;
      for (int64_t r = v_.line_start[size_t(l)]; r < v_.line_start[size_t(l) + 1]; ++r) {
        events_.push_back({v_.runs[size_t(r)].begin, b});
        events_.push_back({v_.runs[size_t(r)].end, b});
      }
    }
    if (events_.empty()) return;
    std::sort(events_.begin(), events_.end(), [](const Event& a, const Event& b) { return a.pos < b.pos; });
    // Segments [t_m, t_m+1) of constant column pattern P_m (bit b: line b inside); a line's run
    // ends never coincide with its next begin (runs are non-adjacent), so toggling is exact.
    segments_.clear();
    int pattern = 0;
    for (size_t e = 0; e < events_.size();) {
      const int64_t pos = events_[e].pos;
      const int before = pattern;
      for (; e < events_.size() && events_[e].pos == pos; ++e) pattern ^= 1 << events_[e].line;
      if ((before ^ pattern) & 1) vertex(2 * pos - 1, 2 * j, 2 * k);  // x-edge of line (j, k)
      segments_.push_back({pos, pattern});
    }
    cubes(segments_.front().start - 1, 1, 0, segments_.front().pattern, j, k);
    for (size_t m = 0; m + 1 < segments_.size(); ++m) {
      const Segment& s = segments_[m];
      const int64_t end = segments_[m + 1].start;
      cubes(s.start, end - 1 - s.start, s.pattern, s.pattern, j, k);
      cubes(end - 1, 1, s.pattern, segments_[m + 1].pattern, j, k);
      if (((s.pattern ^ (s.pattern >> 1)) & 1) != 0) vertex_row(s.start, end, 2 * j + 1, 2 * k);  // y-edges
      if (((s.pattern ^ (s.pattern >> 2)) & 1) != 0) vertex_row(s.start, end, 2 * j, 2 * k + 1);  // z-edges
    }
  }

 private:
  struct Event {
    int64_t pos;
    int line;
  };
  struct Segment {
    int64_t start;
    int pattern;
  };

  static void add(PlaneFamily& f, int64_t plane, int64_t row, int64_t value) {
    const size_t n = size_t((plane - f.plane_base) * f.rows + (row - f.row_base));
    f.min[n] = std::min(f.min[n], int32_t(value));
    f.max[n] = std::max(f.max[n], int32_t(value));
  }

  // `count` cubes from lowest corner (first, j, k) on, whose columns at i and i + 1 have patterns
  // a and b (bit 0: line (j,k), 1: (j+1,k), 2: (j,k+1), 3: (j+1,k+1)).
  void cubes(int64_t first, int64_t count, int a, int b, int64_t j, int64_t k) {
    if (count <= 0) return;
    // Column bit (dj + 2 dk) goes to case bit (di + 2 dj + 4 dk).
    auto spread = [](int p) { return (p & 1) | ((p & 2) << 1) | ((p & 4) << 2) | ((p & 8) << 3); };
    const int c = spread(a) | (spread(b) << 1);
    if (c == 0 || c == 255) return;
    out_.cube_count[size_t(c)] += count;
    out_.corner_sum[size_t(c)][0] += (2 * first + count - 1) * count / 2;
    out_.corner_sum[size_t(c)][1] += j * count;
    out_.corner_sum[size_t(c)][2] += k * count;
  }

  const RunLengthVolume& v_;
  MaskSurfaceSweep& out_;
  std::vector<Event> events_;
  std::vector<Segment> segments_;
};

// Each plane's hull from its rows' two ends.
void build_hulls(PlaneFamily& f) {
  f.hulls.assign(size_t(f.planes), {});
  f.on_hull.assign(f.min.size(), 0);
  std::vector<LatticeRow> rows;
  for (int64_t p = 0; p < f.planes; ++p) {
    rows.clear();
    for (int64_t r = 0; r < f.rows; ++r) {
      const size_t n = size_t(p * f.rows + r);
      if (f.min[n] <= f.max[n]) rows.push_back({r + f.row_base, f.min[n], f.max[n]});
    }
    std::vector<LatticePoint> hull = lattice_hull_of_rows(rows);
    for (const LatticePoint& h : hull) {
      const size_t n = size_t(p * f.rows + (h.u - f.row_base));
      f.on_hull[n] |= uint8_t((h.v == f.min[n] ? 1 : 0) | (h.v == f.max[n] ? 2 : 0));
    }
    f.hulls[size_t(p)] = std::move(hull);
  }
}

}  // namespace

bool PlaneFamily::is_hull_vertex(int64_t plane, int64_t row, int64_t value) const {
  const int64_t p = plane - plane_base, r = row - row_base;
  if (p < 0 || p >= planes || r < 0 || r >= rows) return false;
  const size_t n = size_t(p * rows + r);
  return (value == min[n] && (on_hull[n] & 1)) || (value == max[n] && (on_hull[n] & 2));
}

static Result<MaskSurfaceSweep> mask_surface_sweep_here(const RunLengthVolume& volume) {
  SOIQ_RETURN_IF_ERROR(check_volume(volume));
  MaskSurfaceSweep out;
  const auto& d = volume.geometry.dims;
  for (int64_t l = 0; l < volume.line_count(); ++l) {
    const int64_t first = volume.line_start[size_t(l)], last = volume.line_start[size_t(l) + 1];
    if (first == last) continue;
    const std::array<int64_t, 3> lo{volume.runs[size_t(first)].begin, l % d[1], l / d[1]};
    const std::array<int64_t, 3> hi{volume.runs[size_t(last) - 1].end - 1, l % d[1], l / d[1]};
    for (size_t a = 0; a < 3; ++a) {
      out.lo[a] = out.empty ? lo[a] : std::min(out.lo[a], lo[a]);
      out.hi[a] = out.empty ? hi[a] : std::max(out.hi[a], hi[a]);
    }
    out.empty = false;
  }
  if (out.empty) return out;
  out.families[0] = make_family(0, 2, 1, out.lo, out.hi);
  out.families[1] = make_family(1, 2, 0, out.lo, out.hi);
  out.families[2] = make_family(2, 1, 0, out.lo, out.hi);
  Sweep sweep(volume, out);
  for (int64_t k = out.lo[2] - 1; k <= out.hi[2]; ++k) {
    for (int64_t j = out.lo[1] - 1; j <= out.hi[1]; ++j) sweep.quad(j, k);
  }
  for (PlaneFamily& f : out.families) build_hulls(f);
  return out;
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
Result<MaskSurfaceSweep> mask_surface_sweep(const RunLengthVolume& volume) {
  return cpu_dispatch([&] { return mask_surface_sweep_here(volume); });
}

}  // namespace soiq
