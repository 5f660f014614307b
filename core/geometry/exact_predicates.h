#pragma once
// Exact signs of the two determinants the line filler's decisions rest on, for double inputs.
// Each first evaluates in double with a forward error bound (the classic adaptive-predicate
// filter); only when the value is within that bound of zero is the sign computed exactly, with
// floating-point expansions (sums of non-overlapping doubles, built with error-free TwoSum and an
// FMA-based TwoProduct). So a tie is a tie, never an artifact of rounding.
//
// Exact for finite inputs whose intermediate products neither overflow nor underflow (any
// coordinates in millimetres or voxel indices qualify). Thread-safe; no allocation on the fast path.

#include <cmath>

namespace soiq {

// Sign (-1, 0, +1) of (b1 - a1)(p2 - a2) - (b2 - a2)(p1 - a1): +1 when p lies to the left of the
// directed line a -> b in the plane of coordinates (1, 2).
int orient2d_sign(double a1, double a2, double b1, double b2, double p1, double p2);

// The exact sign alone, without the filter.
int orient2d_sign_exact(double a1, double a2, double b1, double b2, double p1, double p2);

// The same as orient2d_sign with the double evaluation and its error bound supplied by a caller
// that already has them (the hot loop of the 1D method computes the value for interpolation
// anyway). Inline: the filter is the hot path, the exact evaluation the rare one.
inline int orient2d_sign_filtered(double value, double error_bound, double a1, double a2, double b1, double b2,
                                  double p1, double p2) {
  if (value > error_bound) return 1;
  if (value < -error_bound) return -1;
  // Both products exactly zero (a factor was a difference of equal doubles): an exact zero.
  if (error_bound == 0) return 0;
  return orient2d_sign_exact(a1, a2, b1, b2, p1, p2);
}

// The error bound of the double evaluation of orient2d from its two products t1 - t2.
inline double orient2d_error_bound(double t1, double t2) {
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (3.0 + 16.0 * kEps) * kEps;
  return kBound * (std::fabs(t1) + std::fabs(t2));
}

// Sign of the triple product ((b - a) x (c - a)) . (d - a), i.e. det[b-a; c-a; d-a]: +1 when d is
// on the side of the plane abc that its normal (b - a) x (c - a) points to.
int orient3d_sign(const double a[3], const double b[3], const double c[3], const double d[3]);

}  // namespace soiq
