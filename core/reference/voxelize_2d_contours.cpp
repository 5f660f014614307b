#include "core/reference/voxelize_2d_contours.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/reference/index_space_vertices.h"
#include "core/reference/runs_of_line.h"

namespace soiq {

namespace {

using Real = long double;  // as the 3D oracle: at least as exact as the double production path

struct Point2 {
  Real x = 0, y = 0;
};

// A contour segment in the plane z = k, directed so that the solid lies to its left (seen from
// +z, outward normals): it runs towards +y exactly where the triangle's n_x > 0.
struct Segment {
  Point2 from, to;
};

// Integer n in [0, count) with lo <= n < hi: the slices (rows) that a z (y) range straddles when a
// coordinate equal to n counts as below n + e.
void straddled_range(double lo, double hi, int64_t count, int64_t& first, int64_t& last) {
  first = int64_t(std::ceil(std::clamp(lo, -1.0, double(count))));
  last = int64_t(std::ceil(std::clamp(hi, -1.0, double(count)))) - 1;
  first = std::max<int64_t>(first, 0);
  last = std::min<int64_t>(last, count - 1);
}

// Where the edge lo -> hi (lo_z <= k < hi_z) meets the plane z = k. Always interpolated from the
// lower endpoint, so the two triangles sharing the edge get the same point bit for bit.
Point2 cut_edge(const Vec3& lo, const Vec3& hi, Real k) {
  const Real t = (k - Real(lo[2])) / (Real(hi[2]) - Real(lo[2]));
  return {Real(lo[0]) + t * (Real(hi[0]) - Real(lo[0])), Real(lo[1]) + t * (Real(hi[1]) - Real(lo[1]))};
}

// The segment triangle abc leaves in the plane z = k + e^2, if it straddles it. Walking the
// boundary a -> b -> c -> a, the walk goes up through the plane once and down once; for an
// outward-facing triangle the contour runs from the down point to the up point (solid on the left).
bool cut_triangle(const Vec3& a, const Vec3& b, const Vec3& c, Real k, Segment& out) {
  const Vec3* v[3] = {&a, &b, &c};
  bool have_up = false, have_down = false;
  for (int e = 0; e < 3; ++e) {
    const Vec3& p = *v[e];
    const Vec3& q = *v[(e + 1) % 3];
    const bool p_above = Real(p[2]) > k, q_above = Real(q[2]) > k;
    if (!p_above && q_above) {
      out.to = cut_edge(p, q, k);
      have_up = true;
    } else if (p_above && !q_above) {
      out.from = cut_edge(q, p, k);
      have_down = true;
    }
  }
  return have_up && have_down;
}

// CSR lists: items of bucket n are items[start[n] .. start[n+1]).
struct Buckets {
  std::vector<int64_t> start;
  std::vector<int32_t> items;
};

// Buckets items 0..count-1 by the integer range range_of(item) returns (first, last inclusive).
template <typename RangeOf>
Buckets bucket(int64_t buckets, int64_t count, RangeOf range_of) {
  Buckets out;
  out.start.assign(size_t(buckets) + 1, 0);
  for (int64_t t = 0; t < count; ++t) {
    const auto [first, last] = range_of(t);
    for (int64_t n = first; n <= last; ++n) ++out.start[size_t(n) + 1];
  }
  for (int64_t n = 0; n < buckets; ++n) out.start[size_t(n) + 1] += out.start[size_t(n)];
  out.items.resize(size_t(out.start.back()));
  std::vector<int64_t> cursor(out.start.begin(), out.start.end() - 1);
  for (int64_t t = 0; t < count; ++t) {
    const auto [first, last] = range_of(t);
    for (int64_t n = first; n <= last; ++n) out.items[size_t(cursor[size_t(n)]++)] = int32_t(t);
  }
  return out;
}

}  // namespace

Result<RunLengthVolume> voxelize_2d_contours(const TriangleMesh& mesh, const ImageGeometry& geometry, FillRule rule) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<Vec3> u, index_space_vertices(mesh, geometry));
  const int64_t nx = geometry.dims[0], ny = geometry.dims[1], nz = geometry.dims[2];

  const Buckets by_slice = bucket(nz, int64_t(mesh.triangles.size()), [&](int64_t t) {
    const auto& tri = mesh.triangles[size_t(t)];
    const double z0 = u[size_t(tri[0])][2], z1 = u[size_t(tri[1])][2], z2 = u[size_t(tri[2])][2];
    int64_t first, last;
    straddled_range(std::min({z0, z1, z2}), std::max({z0, z1, z2}), nz, first, last);
    return std::pair{first, last};
  });

  RunLengthVolume out = empty_volume(geometry);
  std::vector<uint8_t> inside(static_cast<size_t>(nx));
  std::vector<Segment> segments;
  for (int64_t k = 0; k < nz; ++k) {
    // 1. The contour of slice k.
    segments.clear();
    for (int64_t n = by_slice.start[size_t(k)]; n < by_slice.start[size_t(k) + 1]; ++n) {
      const auto& tri = mesh.triangles[size_t(by_slice.items[size_t(n)])];
      Segment s;
      if (cut_triangle(u[size_t(tri[0])], u[size_t(tri[1])], u[size_t(tri[2])], Real(k), s)) segments.push_back(s);
    }
    // Rows are bucketed from the y range rounded to double and widened by one row on each side
    // (a long double y within 1e-16 of an integer may round onto it); the exact straddle test
    // below decides, the bucket is only a candidate list.
    const Buckets by_row = bucket(ny, int64_t(segments.size()), [&](int64_t s) {
      const Segment& g = segments[size_t(s)];
      int64_t first, last;
      straddled_range(double(std::min(g.from.y, g.to.y)) - 1, double(std::max(g.from.y, g.to.y)) + 1, ny, first, last);
      return std::pair{first, last};
    });

    // 2. One ray per voxel centre of the slice.
    for (int64_t j = 0; j < ny; ++j) {
      const int64_t l = j + ny * k;
      out.line_start[size_t(l)] = int64_t(out.runs.size());
      const int64_t first = by_row.start[size_t(j)], last = by_row.start[size_t(j) + 1];
      if (first == last) continue;
      for (int64_t i = 0; i < nx; ++i) {
        int64_t winding = 0, count = 0;
        for (int64_t c = first; c < last; ++c) {
          const Segment& g = segments[size_t(by_row.items[size_t(c)])];
          // Endpoints on the row count as below it (y = j + e).
          const bool from_above = g.from.y > Real(j), to_above = g.to.y > Real(j);
          if (from_above == to_above) continue;
          const Point2& lo = from_above ? g.to : g.from;
          const Point2& hi = from_above ? g.from : g.to;
          const Real x = lo.x + (Real(j) - lo.y) * (hi.x - lo.x) / (hi.y - lo.y);
          if (x > Real(i)) {
            // Ahead of the centre: +1 for a leaving crossing (segment towards +y), as in 3D.
            winding += to_above ? 1 : -1;
            ++count;
          }
        }
        inside[size_t(i)] = rule == FillRule::kNonZero ? winding != 0 : (count & 1) != 0;
      }
      const std::vector<Run> runs = runs_of_line(inside.data(), nx);
      out.runs.insert(out.runs.end(), runs.begin(), runs.end());
    }
  }
  out.line_start[size_t(ny * nz)] = int64_t(out.runs.size());
  return out;
}

}  // namespace soiq
