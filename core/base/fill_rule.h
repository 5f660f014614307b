#pragma once
// How crossings along a line decide inside (docs/DESIGN.md step 4).

namespace soiq {

enum class FillRule {
  kNonZero,  // inside where the winding number (sum of +1 entering / -1 leaving) is nonzero
  kEvenOdd,  // inside where the number of crossings so far is odd (RTSTRUCT contours, XOR)
};

}  // namespace soiq
