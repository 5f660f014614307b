#include "core/geometry/symmetric_eigenvalues.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace soiq {

Vec3 symmetric_eigenvalues(const Mat3& m) {
  // Work on a full symmetric copy built from the upper triangle.
  double a[3][3];
  for (int r = 0; r < 3; ++r) {
    for (int c = r; c < 3; ++c) a[r][c] = a[c][r] = m[r][c];
  }
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = std::fabs(a[0][1]) + std::fabs(a[0][2]) + std::fabs(a[1][2]);
    const double diag = std::fabs(a[0][0]) + std::fabs(a[1][1]) + std::fabs(a[2][2]);
    // Converged when the off-diagonal mass no longer changes the diagonal in double precision.
    if (off == 0 || diag + off == diag) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        const double apq = a[p][q];
        if (apq == 0) continue;
        // Rotation that annihilates a[p][q] (the stable small-angle choice of t = tan(theta)).
        const double theta = (a[q][q] - a[p][p]) / (2 * apq);
        const double t = std::copysign(1.0, theta) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // columns p and q: A <- A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // rows p and q: A <- J^T A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        a[p][q] = a[q][p] = 0;  // exactly zero by construction; drop the rounding residue
      }
    }
  }
  Vec3 l{a[0][0], a[1][1], a[2][2]};
  std::sort(l.begin(), l.end(), std::greater<double>());
  return l;
}

}  // namespace soiq
