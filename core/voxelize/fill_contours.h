#pragma once
// Planar contours -> volume model, through the same line filler as the 1D method (docs/DESIGN.md step 7).
// DICOM RT Structure Set CLOSED_PLANAR contours are already the paper's 2D contours: each lies in
// one slice plane of the referenced image, so only step 4 (fill between crossings) is left.
//
// Inputs   contours: closed polygons in LPS mm (the last point joins the first), each lying in a
//          plane k = const of `geometry` (within `slice_tolerance_voxels` of an integer k);
//          geometry: the referenced series' grid; rule: even-odd by default, so holes and inner
//          contours subtract whatever their orientation (XOR, as RTSTRUCT tools agree).
// Output   voxel (i,j,k) inside iff its centre is inside the contours of slice k by the rule. The
//          row line is perturbed to y = j + e, so a vertex exactly on a row line is counted by one
//          of its two edges; a centre exactly on an entering edge is inside, on a leaving edge not.
//          Contours on slices outside the grid are counted in `contours_outside_grid`, not filled.
// Errors   INVALID_ARGUMENT: fewer than 3 points, non-finite coordinates, a contour not in one
//          slice plane (message gives the contour's index and its offset in voxels).
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
};

Result<ContourFill> fill_contours(const std::vector<PlanarContour>& contours, const ImageGeometry& geometry,
                                  FillRule rule = FillRule::kEvenOdd, double slice_tolerance_voxels = 0.25,
                                  int64_t max_voxels = kDefaultMaxVoxels);

}  // namespace soiq
