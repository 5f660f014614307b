#pragma once
// The regions in which intensity features are measured (docs/DESIGN.md "Features": region inside,
// shell(r mm); and core(r mm), its inward twin), all computed from a structure's voxels on its own grid:
//   inside     the structure itself;
//   shell(r)   the voxels not inside whose centre lies within r mm (Euclidean, in mm, each axis with
//              its own spacing: not a dilation by a number of voxels) of an inside voxel centre;
//   core(r)    the inside voxels whose centre lies farther than r mm from every outside voxel centre
//              (deeper than r).
// Distances come from the exact separable Euclidean distance transform (distance_transform.h) over
// the structure's bounding box grown by r, so the cost follows the structure, not the image; when
// the ball's cross section is small, a shell is dilated and a core eroded on the runs instead
// (ball_morphology.h), with the same distances and tie rule.
//
// Inputs
//   structure  a RunLengthVolume with a valid geometry (validate_geometry) and line_start of
//              ny*nz+1 entries.
//   spec       the region; radius_mm finite and > 0 for shell and core, ignored for inside.
//   options    threads (>= 1) for the distance transform; max_box_voxels bounds the grown box
//              (up to 10 bytes per box voxel are allocated); method (RegionMethod below). A radius
//              beyond the grid selects what twice the grid's diagonal does: the same voxels.
// Output
//   A RunLengthVolume on the structure's grid. "Within r" includes distances equal to r (to 1e-12
//   relative, so ties such as 3 x 0.7 mm = 2.1 mm are decided the same way on every machine);
//   "farther than r" excludes them. The region may be empty (a shell of an empty structure, the core
//   of a structure thinner than 2r): the intensity step reports that (resample.h).
// Errors
//   INVALID_ARGUMENT    bad geometry, or a run table that does not fit the grid; radius not finite
//                       or <= 0 for shell/core.
//   RESOURCE_EXHAUSTED  the grown box has more than options.max_box_voxels voxels.
// Cost
//   By the transform O(runs + box voxels), memory up to 10 bytes per box voxel; on the runs
//   O(box lines x ball offset lines x runs per line), no box memory. The cheaper is taken
//   (BENCHMARKS.md: SM1 core(3) 1.2 ms on the runs, 19 ms by the transform). Thread-safe.
// Caveats
//   The grid is the world: voxels outside it do not exist. A shell is clipped at the grid border,
//   and a structure touching the border is not eroded from that side by core(r) (there is no
//   outside voxel there). Distances are between voxel centres, so a shell thinner than the spacing
//   along an axis can be empty along that axis (shell(2) above a face normal to a 2.5 mm axis), and
//   shell(r) volumes run below the analytic offset volume (core(r) above it) by a fraction of the
//   spacing times the surface area: sphere R = 20 mm, shell(2) on a 1 mm grid -15 %, 0.5 mm -8 %,
//   0.25 mm -3 %; core(2) +4 %, +2 %, +1 % (tests/core/regions_sphere_test.cpp).
//   Decided, not overlooked: centre-to-centre distance is the binary dilation by a ball of r mm
//   that peritumoral-ring studies use, it gives a mask and the surface it came from the same
//   shell, and it needs nothing but the voxels. Distances to the stored surface would track the
//   analytic volume more closely, but only for structures that have a surface, and would make
//   shell(r) of a mask and of its own marching-cubes surface differ.

#include <cstdint>
#include <string>
#include <string_view>

#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq {

enum class RegionKind { kInside, kShell, kCore };

struct RegionSpec {
  RegionKind kind = RegionKind::kInside;
  double radius_mm = 0;  // shell and core only
};

// How a shell or core is built; every way selects the same voxels. kRuns dilates (shell) or erodes
// (core) the runs with the ball (ball_morphology.h); kTransform thresholds the distance transform of
// the grown box; kCheapest takes the one its cost model expects to be faster (regions.cpp).
enum class RegionMethod { kCheapest, kRuns, kTransform };

struct RegionOptions {
  int threads = 1;
  // Bounds the work either way: the transform allocates the grown box, and the runs' cost also
  // grows with it where they are taken.
  int64_t max_box_voxels = 200'000'000;
  RegionMethod method = RegionMethod::kCheapest;
};

// "inside", "shell:R" or "core:R" with R in mm (e.g. "shell:5"). INVALID_ARGUMENT naming the
// accepted forms otherwise, or when R is not a finite number > 0.
Result<RegionSpec> parse_region(std::string_view text);

// The inverse of parse_region: "inside", "shell:5", "core:2.5".
std::string region_name(const RegionSpec& spec);

Result<RunLengthVolume> region(const RunLengthVolume& structure, const RegionSpec& spec,
                               const RegionOptions& options = {});

// The way kCheapest takes for this structure and region (kRuns or kTransform; kRuns for inside and
// for an empty structure, which need neither), for benchmarks and tests. Errors as region()'s.
Result<RegionMethod> cheapest_region_method(const RunLengthVolume& structure, const RegionSpec& spec);

}  // namespace soiq
