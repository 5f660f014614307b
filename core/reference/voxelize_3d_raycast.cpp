#include "core/reference/voxelize_3d_raycast.h"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/reference/index_space_vertices.h"
#include "core/reference/runs_of_line.h"

namespace soiq {

namespace {

// Every decision is a sign, computed exactly with respect to the index-space doubles: a floating-
// point filter with a proven error bound answers when it can, GMP rationals (exact, and written
// independently of the production path's expansions) when it cannot. So this oracle has no
// near-tie zone: it is wrong only if the bound below is.
//
// Error bounds, with u = 2^-53 the unit roundoff and round-to-nearest (no FMA contraction:
// core/CMakeLists.txt builds core/reference/ with -ffp-contract=off). A value reached through n
// roundings of exact inputs is off by at most gamma_n = n u / (1 - n u) of the sum of the
// magnitudes of its exact terms (Higham, "Accuracy and Stability of Numerical Algorithms", 3.1).
//   edge function: differences, product, subtraction   n = 4, below 8 u x (|t1| + |t2|);
//   3x3 determinant: differences, 2 products, 2 subtractions/sums per cofactor expansion
//                                                      n = 8, below 16 u x its permanent.
// The margin (2x) also covers the rounding of the bound itself. Underflow adds at most half a
// subnormal per operation, times whatever factor multiplies it later: kUnderflowSlack, scaled by
// those factors in the determinant. An overflow gives inf or NaN, which fails the filter and goes
// exact.
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;
constexpr double kEdgeBound = 8 * kU;
constexpr double kOrientBound = 16 * kU;
constexpr double kUnderflowSlack = 64 * std::numeric_limits<double>::denorm_min();

// Whether v is a multiple of 2^-8 with |v| < 2^16 (the scaling by 2^8 is exact).
bool on_fine_lattice(double v) {
  const double scaled = std::ldexp(v, 8);
  return std::abs(v) < 65536 && scaled == std::trunc(scaled);
}

// Sign of the edge function of the directed edge a -> b at (py, pz), in the (y, z) projection:
//   E(P) = (b_y - a_y)(P_z - a_z) - (b_z - a_z)(P_y - a_y),
// positive when P lies to the left of a -> b.
int edge_function_sign(const Vec3& a, const Vec3& b, double py, double pz) {
  const double t1 = (b[1] - a[1]) * (pz - a[2]);
  const double t2 = (b[2] - a[2]) * (py - a[1]);
  const double e = t1 - t2;
  const double bound = kEdgeBound * (std::abs(t1) + std::abs(t2)) + kUnderflowSlack;
  if (e > bound) return 1;
  if (e < -bound) return -1;
  // Lattice-aligned meshes put many lines exactly through edges; there every input is a multiple
  // of 2^-8 below 2^16, so the differences have <= 25 significant bits, the products <= 50 and e
  // <= 51: e was computed exactly.
  if (on_fine_lattice(a[1]) && on_fine_lattice(a[2]) && on_fine_lattice(b[1]) && on_fine_lattice(b[2]) &&
      on_fine_lattice(py) && on_fine_lattice(pz)) {
    return (e > 0) - (e < 0);
  }
  const mpq_class ay(a[1]), az(a[2]);
  return sgn((mpq_class(b[1]) - ay) * (mpq_class(pz) - az) - (mpq_class(b[2]) - az) * (mpq_class(py) - ay));
}

// The sign of E at the perturbed point (py + e, pz + e^2), e -> 0+: there
// E + (b_y - a_y) e^2 - (b_z - a_z) e, so a zero E takes the sign of -(b_z - a_z), or of
// (b_y - a_y) when b_z == a_z (compared, not subtracted: exact). 0 only for an edge of zero length.
// The rule is antisymmetric in a and b, so the two triangles sharing an edge get opposite signs and
// a line through the edge is counted by exactly one of them.
int perturbed_edge_sign(const Vec3& a, const Vec3& b, double py, double pz) {
  const int s = edge_function_sign(a, b, py, pz);
  if (s != 0) return s;
  if (b[2] != a[2]) return b[2] > a[2] ? -1 : 1;
  return (b[1] > a[1]) - (b[1] < a[1]);
}

// Sign of det[a - q; b - q; c - q] = (a - q) . ((b - a) x (c - a)) = n . (a - q). Along the row
// line through q, n . (a - p) falls at the rate n_x as p moves in +x and is zero at the crossing x*,
// so this sign is sign(n_x) exactly when x* > q_x, 0 when x* == q_x.
int orientation_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& q) {
  const double adx = a[0] - q[0], ady = a[1] - q[1], adz = a[2] - q[2];
  const double bdx = b[0] - q[0], bdy = b[1] - q[1], bdz = b[2] - q[2];
  const double cdx = c[0] - q[0], cdy = c[1] - q[1], cdz = c[2] - q[2];
  const double bc1 = bdy * cdz, bc2 = bdz * cdy;
  const double ca1 = cdy * adz, ca2 = cdz * ady;
  const double ab1 = ady * bdz, ab2 = adz * bdy;
  const double det = adx * (bc1 - bc2) + bdx * (ca1 - ca2) + cdx * (ab1 - ab2);
  const double permanent = std::abs(adx) * (std::abs(bc1) + std::abs(bc2)) +
                           std::abs(bdx) * (std::abs(ca1) + std::abs(ca2)) +
                           std::abs(cdx) * (std::abs(ab1) + std::abs(ab2));
  const double bound = kOrientBound * permanent + kUnderflowSlack * (1 + std::abs(adx) + std::abs(bdx) + std::abs(cdx));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  const mpq_class qx(q[0]), qy(q[1]), qz(q[2]);
  const mpq_class ex = mpq_class(a[0]) - qx, ey = mpq_class(a[1]) - qy, ez = mpq_class(a[2]) - qz;
  const mpq_class fx = mpq_class(b[0]) - qx, fy = mpq_class(b[1]) - qy, fz = mpq_class(b[2]) - qz;
  const mpq_class gx = mpq_class(c[0]) - qx, gy = mpq_class(c[1]) - qy, gz = mpq_class(c[2]) - qz;
  return sgn(ex * (fy * gz - fz * gy) + fx * (gy * ez - gz * ey) + gx * (ey * fz - ez * fy));
}

// Whether the ray {(x, j, k) : x > i} crosses triangle abc, and how: +1 where n_x > 0 (leaving,
// for outward normals), -1 where n_x < 0 (entering), 0 for no crossing.
int crossing_ahead(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& centre) {
  // The perturbed line meets the triangle iff the point lies strictly inside its (y, z) projection,
  // iff the three perturbed edge signs agree; they then equal sign(n_x), the sign of the projected
  // area. A projection of zero area can never make them agree (its three edge directions sum to
  // zero), so such triangles are skipped without a special case.
  const int s = perturbed_edge_sign(a, b, centre[1], centre[2]);
  if (s == 0 || perturbed_edge_sign(b, c, centre[1], centre[2]) != s ||
      perturbed_edge_sign(c, a, centre[1], centre[2]) != s) {
    return 0;
  }
  // The crossing x is the plane's at the unperturbed (j, k); strictly ahead of the centre or not.
  return orientation_sign(a, b, c, centre) == s ? s : 0;
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
        // (docs/DESIGN.md step 4). Parity is the same either way, as the total count is even.
        int64_t winding = 0, count = 0;
        const Vec3 centre{double(i), double(j), double(k)};
        for (int64_t c = first; c < last; ++c) {
          const auto& tri = mesh.triangles[size_t(buckets.triangles[size_t(c)])];
          const int s = crossing_ahead(u[size_t(tri[0])], u[size_t(tri[1])], u[size_t(tri[2])], centre);
          winding += s;
          count += s != 0;
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
