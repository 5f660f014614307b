#include "core/reference/voxelize_3d_raycast.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/reference/index_space_vertices.h"
#include "core/reference/runs_of_line.h"

namespace soiq {

namespace {

// The oracle computes its predicates in long double (64-bit mantissa) so that it is at least as
// exact as the double-precision production path; they can only disagree within ~1e-15 of a tie.
using Real = long double;

// A signed value and its sign under the symbolic perturbation of the query point.
struct EdgeValue {
  Real value = 0;  // edge function at the unperturbed point (j, k)
  int sign = 0;    // its sign at (j + e, k + e^2), e -> 0+; 0 only for an edge of zero length
};

// Edge function of the directed edge a -> b at the point (py, pz), in the (y, z) projection:
//   E(P) = (b_y - a_y)(P_z - a_z) - (b_z - a_z)(P_y - a_y),
// positive when P lies to the left of a -> b. Evaluated with the endpoints in lexicographic (y, z)
// order and negated when the edge runs the other way, so the two triangles sharing an edge get
// exactly opposite values, rounding included: a line through the edge is counted by one of them.
// At P + (e, e^2): E + (b_y - a_y) e^2 - (b_z - a_z) e, so a zero E takes the sign of
// -(b_z - a_z), or of (b_y - a_y) when b_z == a_z.
EdgeValue edge_value(const Vec3& a, const Vec3& b, Real py, Real pz) {
  const bool swapped = (b[1] < a[1]) || (b[1] == a[1] && b[2] < a[2]);
  const Vec3& lo = swapped ? b : a;
  const Vec3& hi = swapped ? a : b;
  const Real dy = Real(hi[1]) - Real(lo[1]);
  const Real dz = Real(hi[2]) - Real(lo[2]);
  Real e = dy * (pz - Real(lo[2])) - dz * (py - Real(lo[1]));
  int s = (e > 0) - (e < 0);
  if (s == 0) s = dz != 0 ? (dz > 0 ? -1 : 1) : (dy > 0) - (dy < 0);
  if (swapped) {
    e = -e;
    s = -s;
  }
  return {e, s};
}

// The crossing of the perturbed line (x, j + e, k + e^2) with triangle abc, when there is one.
struct Crossing {
  bool hit = false;
  int sign = 0;  // sign of the triangle normal's x component: +1 leaving, -1 entering
  Real x = 0;    // where the unperturbed line meets the triangle's plane
};

Crossing cross_line(const Vec3& a, const Vec3& b, const Vec3& c, Real py, Real pz) {
  const EdgeValue ab = edge_value(a, b, py, pz);
  const EdgeValue bc = edge_value(b, c, py, pz);
  const EdgeValue ca = edge_value(c, a, py, pz);
  // Strictly inside the projection iff the three perturbed signs agree; they then equal the sign
  // of the projected signed area (n_x). A projection of zero area can never make them agree
  // (its three edge directions sum to zero), so such triangles are skipped without a special case.
  if (ab.sign == 0 || ab.sign != bc.sign || bc.sign != ca.sign) return {};
  // Barycentric weights from the same edge values; the sum is 2x the projected area. x is written
  // as a_x plus differences so a triangle of constant x gives exactly that x (box faces on
  // integer planes stay exactly on them).
  const Real area2 = ab.value + bc.value + ca.value;
  const Real x = Real(a[0]) + (ca.value * (Real(b[0]) - Real(a[0])) + ab.value * (Real(c[0]) - Real(a[0]))) / area2;
  return {true, ab.sign, x};
}

// Integer points n in [0, count) with lo <= n <= hi (the closed range, clamped to the grid).
void integer_range(double lo, double hi, int64_t count, int64_t& first, int64_t& last) {
  first = int64_t(std::ceil(std::clamp(lo, -1.0, double(count))));
  last = int64_t(std::floor(std::clamp(hi, -1.0, double(count))));
  first = std::max<int64_t>(first, 0);
  last = std::min<int64_t>(last, count - 1);
}

// Candidate triangles per line (j, k), l = j + ny * k: every triangle whose closed (y, z) bounding
// box holds the integer point (j, k), a superset of the triangles the perturbed line crosses.
struct LineBuckets {
  std::vector<int64_t> start;  // lines + 1 offsets into `triangles`
  std::vector<int32_t> triangles;
};

LineBuckets bucket_by_line(const TriangleMesh& mesh, const std::vector<Vec3>& u, int64_t ny, int64_t nz) {
  LineBuckets out;
  out.start.assign(size_t(ny * nz + 1), 0);
  std::vector<int64_t> cursor;
  for (int pass = 0; pass < 2; ++pass) {  // pass 0 counts, pass 1 fills
    if (pass == 1) {
      for (size_t l = 0; l + 1 < out.start.size(); ++l) out.start[l + 1] += out.start[l];
      out.triangles.resize(size_t(out.start.back()));
      cursor.assign(out.start.begin(), out.start.end() - 1);
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const Vec3 &a = u[size_t(tri[0])], &b = u[size_t(tri[1])], &c = u[size_t(tri[2])];
      int64_t j0, j1, k0, k1;
      integer_range(std::min({a[1], b[1], c[1]}), std::max({a[1], b[1], c[1]}), ny, j0, j1);
      integer_range(std::min({a[2], b[2], c[2]}), std::max({a[2], b[2], c[2]}), nz, k0, k1);
      for (int64_t k = k0; k <= k1; ++k) {
        for (int64_t j = j0; j <= j1; ++j) {
          const int64_t l = j + ny * k;
          if (pass == 0) {
            ++out.start[size_t(l) + 1];
          } else {
            out.triangles[size_t(cursor[size_t(l)]++)] = int32_t(t);
          }
        }
      }
    }
  }
  return out;
}

}  // namespace

Result<RunLengthVolume> voxelize_3d_raycast(const TriangleMesh& mesh, const ImageGeometry& geometry, FillRule rule) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<Vec3> u, index_space_vertices(mesh, geometry));
  const int64_t nx = geometry.dims[0], ny = geometry.dims[1], nz = geometry.dims[2];
  const LineBuckets buckets = bucket_by_line(mesh, u, ny, nz);

  RunLengthVolume out = empty_volume(geometry);
  std::vector<uint8_t> inside(static_cast<size_t>(nx));
  for (int64_t k = 0; k < nz; ++k) {
    for (int64_t j = 0; j < ny; ++j) {
      const int64_t l = j + ny * k;
      out.line_start[size_t(l)] = int64_t(out.runs.size());
      const int64_t first = buckets.start[size_t(l)], last = buckets.start[size_t(l) + 1];
      if (first == last) continue;
      for (int64_t i = 0; i < nx; ++i) {
        // The ray from centre (i, j, k) along +x. With outward normals the winding number at the
        // centre is sum(crossings at x <= i, +1 entering (n_x < 0), -1 leaving); a closed surface's
        // crossings sum to zero, so it equals the sum of sign(n_x) over crossings strictly ahead,
        // x > i. Hence a centre on an entering crossing is inside, one on a leaving crossing is not
        // (DESIGN.md step 4). Parity is the same either way, as the total count is even.
        int64_t winding = 0, count = 0;
        for (int64_t c = first; c < last; ++c) {
          const auto& tri = mesh.triangles[size_t(buckets.triangles[size_t(c)])];
          const Crossing x = cross_line(u[size_t(tri[0])], u[size_t(tri[1])], u[size_t(tri[2])], Real(j), Real(k));
          if (x.hit && x.x > Real(i)) {
            winding += x.sign;
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
