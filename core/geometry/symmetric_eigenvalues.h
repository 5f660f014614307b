#pragma once
// Eigenvalues of a real symmetric 3x3 matrix, for the principal axes of a structure (IBSI
// "major/minor/least axis length", docs/DESIGN.md "Features").
//
// Inputs   m: symmetric (only the upper triangle m[r][c], r <= c, is read), finite entries.
// Output   the three eigenvalues, sorted descending: l[0] >= l[1] >= l[2].
// Method   cyclic Jacobi rotations (Golub & Van Loan, "Matrix Computations", 4th ed., 8.5) until
//          the off-diagonal part is below the rounding of the diagonal; each eigenvalue is then
//          accurate to a few ulps of the largest |eigenvalue|, with no cancellation trouble for
//          nearly equal eigenvalues (where the analytic trigonometric formula loses digits).
// Errors   none: a non-finite entry gives non-finite eigenvalues.
// Cost     O(1) (at most 50 sweeps of 3 rotations; 5-6 sweeps in practice). Thread-safe.

#include "core/base/vec3.h"

namespace soiq {

Vec3 symmetric_eigenvalues(const Mat3& m);

}  // namespace soiq
