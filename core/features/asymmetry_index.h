#pragma once
// The asymmetry index of a feature between a structure and its contralateral twin (docs/DESIGN.md
// "Features"): (L - R) / ((L + R) / 2), i.e. the difference relative to the pair's mean.
//
// Inputs   left, right: the same feature of the left and right structure (any unit, the same one);
//          finite.
// Output   A value in [-2, 2] when both are >= 0; 0 when they are equal.
// Errors   INVALID_ARGUMENT  a NaN or infinite input; L + R == 0 (the mean is zero, so the index is
//                            undefined: the message says so, e.g. for two empty shells).
// Cost     O(1). Thread-safe.
// Caveats  Meant for nonnegative features (volumes, uptakes). With L and R of opposite sign the index
//          is defined but unbounded as L + R nears 0.

#include "core/base/status.h"

namespace soiq {

Result<double> asymmetry_index(double left, double right);

}  // namespace soiq
