#include "core/geometry/exact_predicates.h"

#include <cmath>

namespace soiq {

namespace {

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53, half an ulp of 1

// a + b = s + e exactly (Knuth's TwoSum: no precondition on magnitudes).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}

// a * b = p + e exactly, by a fused multiply-add.
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

// A short list of doubles whose exact sum is a value (at most 8 terms here: a product of two
// two-term differences has 4 exact products of 2 terms each).
struct Terms {
  double t[8];
  int n = 0;
  void push(double v) { t[n++] = v; }
};

// b - a as an exact two-term list.
Terms diff(double b, double a) {
  Terms d;
  double s, e;
  two_sum(b, -a, s, e);
  d.push(s);
  if (e != 0) d.push(e);
  return d;
}

// A value as an exact sum of doubles. The sign of a sum of many terms is found by growing a
// non-overlapping expansion term by term (Shewchuk's grow-expansion with zero elimination, done
// in place): each TwoSum keeps its rounding error as a smaller component, so the largest
// component carries the sign. Fixed storage: the exact path never allocates.
class ExactSum {
 public:
  void add(double t) {
    if (t == 0) return;
    int k = 0;
    double q = t;
    for (int i = 0; i < n_; ++i) {
      double s, e;
      two_sum(q, parts_[i], s, e);
      if (e != 0) parts_[k++] = e;  // k <= i: writing in place is safe
      q = s;
    }
    if (q != 0) parts_[k++] = q;
    n_ = k;
  }
  // Adds the exact product of the term lists x and y (times `scale`, which must be +1 or -1).
  void add_product(const double* x, int nx, const double* y, int ny, double scale = 1) {
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        double p, e;
        two_product(x[i], y[j], p, e);
        add(scale * p);
        add(scale * e);
      }
    }
  }
  void add_product(const Terms& x, const Terms& y, double scale = 1) { add_product(x.t, x.n, y.t, y.n, scale); }
  int sign() const { return n_ == 0 ? 0 : (parts_[n_ - 1] > 0 ? 1 : -1); }
  const double* parts() const { return parts_; }
  int size() const { return n_; }

 private:
  // A sum of k terms has at most k components; the largest use is orient3d's final sum: three
  // products of a 2-term difference with a minor of up to 16 components, 2 terms each: 192.
  static constexpr int kCapacity = 200;
  double parts_[kCapacity];
  int n_ = 0;
};

int exact_orient2d(double a1, double a2, double b1, double b2, double p1, double p2) {
  ExactSum sum;
  sum.add_product(diff(b1, a1), diff(p2, a2));
  sum.add_product(diff(b2, a2), diff(p1, a1), -1);
  return sum.sign();
}

}  // namespace

int orient2d_sign_exact(double a1, double a2, double b1, double b2, double p1, double p2) {
  return exact_orient2d(a1, a2, b1, b2, p1, p2);
}

int orient2d_sign(double a1, double a2, double b1, double b2, double p1, double p2) {
  const double t1 = (b1 - a1) * (p2 - a2);
  const double t2 = (b2 - a2) * (p1 - a1);
  return orient2d_sign_filtered(t1 - t2, orient2d_error_bound(t1, t2), a1, a2, b1, b2, p1, p2);
}

int orient3d_sign(const double a[3], const double b[3], const double c[3], const double d[3]) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  // u . (v x w), and the sum of the absolute values of its terms for the error bound.
  const double m0 = v[1] * w[2] - v[2] * w[1];
  const double m1 = v[2] * w[0] - v[0] * w[2];
  const double m2 = v[0] * w[1] - v[1] * w[0];
  const double det = u[0] * m0 + u[1] * m1 + u[2] * m2;
  const double permanent = std::abs(u[0]) * (std::abs(v[1] * w[2]) + std::abs(v[2] * w[1])) +
                           std::abs(u[1]) * (std::abs(v[2] * w[0]) + std::abs(v[0] * w[2])) +
                           std::abs(u[2]) * (std::abs(v[0] * w[1]) + std::abs(v[1] * w[0]));
  // The bound for this evaluation order (differences, 2x2 minors, dot product): (7 + 56 eps) eps.
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  // Exact: the 2x2 minors as expansions, then the dot product with u.
  const Terms ux = diff(b[0], a[0]), uy = diff(b[1], a[1]), uz = diff(b[2], a[2]);
  const Terms vx = diff(c[0], a[0]), vy = diff(c[1], a[1]), vz = diff(c[2], a[2]);
  const Terms wx = diff(d[0], a[0]), wy = diff(d[1], a[1]), wz = diff(d[2], a[2]);
  ExactSum total;
  auto add_term = [&total](const Terms& u, const Terms& p, const Terms& q, const Terms& r, const Terms& s) {
    ExactSum minor;  // p*q - r*s
    minor.add_product(p, q);
    minor.add_product(r, s, -1);
    total.add_product(u.t, u.n, minor.parts(), minor.size());
  };
  add_term(ux, vy, wz, vz, wy);
  add_term(uy, vz, wx, vx, wz);
  add_term(uz, vx, wy, vy, wx);
  return total.sign();
}

}  // namespace soiq
