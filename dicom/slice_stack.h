#pragma once
// The grid of a stack of 2D DICOM images (docs/DESIGN.md "Coordinates and grids"): exact geometry from
// Image Position (Patient), Image Orientation (Patient) and Pixel Spacing, the slice spacing from
// the positions, never from Slice Thickness or Spacing Between Slices.
//
// Inputs   slices in any order, each with its position (LPS mm, centre of the first pixel), its
//          orientation (row direction = direction of increasing column index, then column
//          direction), pixel spacing (between rows, between columns; mm), rows and columns, and a
//          label naming it in messages (file name or instance number).
//          single_slice_spacing_mm: the spacing along the normal when there is one slice
//          (Spacing Between Slices or Slice Thickness; 1 when neither is known).
// Output   StackGeometry: the grid with origin = position of the first slice along the normal
//          n = row x column, direction columns (row, column, n), spacing (column spacing, row
//          spacing, mean distance between consecutive slices along n), dims (columns, rows,
//          slices); `order[k]` is the input index of slice k. A stack acquired with gantry tilt
//          (a slice more than the tolerance below off the normal line through the first) gets a
//          sheared grid instead: its k axis the mean step from slice to slice, unit, and
//          spacing[2] that step's length, so voxel (i,j,k)'s centre is slice k's own pixel. An
//          unevenly spaced stack (a step differing from the smallest by more than max(0.01 mm,
//          1%)) gets slice_positions_mm, each slice where it is along the k axis, so again voxel
//          (i,j,k)'s centre is slice k's own pixel.
// Errors   INVALID_ARGUMENT naming the slice(s), the tag and the value: no slices; a position
//          (0020,0032) that is not finite or over 1e6 mm from the origin; an orientation (0020,0037)
//          that is not finite, or (first slice) not two orthonormal vectors to 1e-4; a pixel
//          spacing (0028,0030) that is not finite, not > 0 or over 1000 mm; rows or columns <= 0;
//          a slice whose orientation, pixel spacing, rows or columns differ from the first
//          slice's; two slices at the same position; a lone step of about a whole multiple (>= 2)
//          of the others, which are all equal, in a stack of 4 or more ("1 missing slice(s)
//          between ...": a file is missing); a tilted stack whose slices are
//          not on one line (off by more than that tolerance: "neither stacked along the normal
//          ... nor tilted by one angle") or tilted more than kMaxTiltDegrees. A
//          single_slice_spacing_mm that is not finite and > 0 becomes 1.
// Cost     O(n log n); thread-safe.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq::dicom {

struct SliceInfo {
  Vec3 position_mm{0, 0, 0};                 // Image Position (Patient)
  std::array<double, 6> orientation{};       // Image Orientation (Patient)
  std::array<double, 2> pixel_spacing_mm{};  // Pixel Spacing: between rows, between columns
  int64_t rows = 0, columns = 0;
  std::string label;  // for messages
};

struct StackGeometry {
  ImageGeometry geometry;
  std::vector<size_t> order;  // order[k] = index into the input of slice k
};

Result<StackGeometry> slice_stack(const std::vector<SliceInfo>& slices, double single_slice_spacing_mm = 1.0);

}  // namespace soiq::dicom
