#pragma once
// Planar contours -> volume model, through the same line filler as the 1D method (docs/DESIGN.md step 7).
// DICOM RT Structure Set CLOSED_PLANAR contours are already the paper's 2D contours: each lies in
// one slice plane of the referenced image, so only step 4 (fill between crossings) is left.
//
// Inputs   contours: closed polygons in LPS mm (the last point joins the first), each planar
//          (every point within `planarity_tolerance_mm` of the contour's plane, the median of its
//          points along the slice normal) and lying on or near an image plane k = const of
//          `geometry`: the contour goes to the nearest plane when its own plane is within
//          `slice_tolerance_voxels` of the spacing from it (0.45 by default: a contour midway
//          between two planes belongs to neither, and a whole set of them to another series);
//          geometry: the referenced series' grid; rule: even-odd by default, so holes and inner
//          contours subtract whatever their orientation (XOR, as RTSTRUCT tools agree).
// Output   voxel (i,j,k) inside iff its centre is inside the contours of slice k by the rule. The
//          row line is perturbed to y = j + e, so a vertex exactly on a row line is counted by one
//          of its two edges; a centre exactly on an entering edge is inside, on a leaving edge not.
//          Contours on slices outside the grid are counted in `contours_outside_grid`, not filled.
//          When contours from several planes of their own reach one image plane (drawn on a finer
//          series), the slice keeps those of the plane nearest to it; the others are counted in
//          `contours_superseded`, not filled (XOR-ing near copies of an outline would hollow it).
// Errors   INVALID_ARGUMENT: fewer than 3 points, non-finite coordinates, a contour that is not
//          planar (its largest distance from its plane, in mm) or too far from every image plane
//          (its distance to the nearest, in mm); the message names the contour by its index.
//          Geometry errors as validate_geometry; RESOURCE_EXHAUSTED over max_voxels.
// Cost     O(points + crossings + lines).

#include <cstdint>
#include <vector>

#include "core/base/fill_rule.h"
#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq {

struct PlanarContour {
  std::vector<Vec3> points_mm;  // LPS
};

struct ContourFill {
  RunLengthVolume volume;
  int64_t contours_outside_grid = 0;
  int64_t contours_superseded = 0;
};

// Within DICOM's decimal strings' rounding (1e-6 mm and less) and the ~0.01 mm that planning
// systems' float coordinates drift by; far below a slice spacing.
inline constexpr double kContourPlanarityToleranceMm = 0.1;

Result<ContourFill> fill_contours(const std::vector<PlanarContour>& contours, const ImageGeometry& geometry,
                                  FillRule rule = FillRule::kEvenOdd, double slice_tolerance_voxels = 0.45,
                                  int64_t max_voxels = kDefaultMaxVoxels,
                                  double planarity_tolerance_mm = kContourPlanarityToleranceMm);

}  // namespace soiq
