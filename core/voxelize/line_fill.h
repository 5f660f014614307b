#pragma once
// The line filler shared by the 1D method and the planar-contour fill (docs/DESIGN.md step 4): the
// crossings of one row line -> its runs of inside voxel centres.

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/fill_rule.h"
#include "core/base/run_length_volume.h"

namespace soiq {

// Where a line crosses the surface, reduced to what decides voxels: the first voxel centre at or
// after the crossing (ceil of its exact position, decided by the callers' exact predicates), and
// the direction. Crossings between the same two centres are equivalent for the fill.
struct LineCrossing {
  int64_t first_centre;  // smallest i with x_crossing <= i, clamped to [-1, nx + 1]
  int32_t sign;          // +1 entering (surface normal against the line direction), -1 leaving
};

// Sorts [first, last) by first_centre, then appends to `runs` the half-open runs of voxel centres
// i in [0, nx) whose winding number (sum of signs of crossings at x <= i) is nonzero (kNonZero) or
// whose crossing count at x <= i is odd (kEvenOdd). Runs touching the previous run of the same line are merged,
// so `runs` stays canonical; `line_first_run` is the index in `runs` where this line's runs begin.
// Returns false when the crossings do not balance (winding or parity not back to 0 at the end):
// the surface is open along this line. Appending to `runs` rather than returning a vector keeps the
// hot loop free of allocations; this is the one output parameter of core/.
// Cost: O(n log n) for n crossings (n is tiny: an insertion sort in practice).
bool fill_line(LineCrossing* first, LineCrossing* last, int64_t nx, FillRule rule, int64_t line_first_run,
               std::vector<Run>& runs);

// ceil(x) clamped to [-1, nx + 1] (crossings beyond the grid only need to stay beyond it); clamped
// before the conversion so far-away crossings cannot overflow.
inline int64_t clamped_ceil(double x, int64_t nx) {
  const double c = std::ceil(x);
  if (!(c >= -1.0)) return -1;
  if (c > double(nx + 1)) return nx + 1;
  return int64_t(c);
}

struct LineCrossingAt {
  int64_t line;  // index of the row line in the caller's numbering, in [0, lines)
  LineCrossing crossing;
};

// The runs of many lines: runs of line l are runs[line_start[l] .. line_start[l+1]).
struct LineRuns {
  std::vector<int64_t> line_start;  // lines + 1 entries
  std::vector<Run> runs;
  int64_t unbalanced_lines = 0;  // lines whose crossings did not balance
};

// Groups `crossings` by line (a counting sort, O(crossings + lines)) and fills every line with
// fill_line. Unbalanced lines keep their runs, or have none when `drop_unbalanced` (robust mode's
// abstention).
LineRuns fill_lines(const std::vector<LineCrossingAt>& crossings, int64_t lines, int64_t nx, FillRule rule,
                    bool drop_unbalanced);

// The same for lines [first_line, first_line + lines) of the crossings in several buffers (numbered
// from first_line in the result); crossings of other lines are left out. A line's crossings are
// taken in the order of the parts, then of each part.
LineRuns fill_lines(const std::vector<const std::vector<LineCrossingAt>*>& parts, int64_t first_line, int64_t lines,
                    int64_t nx, FillRule rule, bool drop_unbalanced);

}  // namespace soiq
