#pragma once
// An ImageGeometry from the form image headers store it in: one LPS vector per voxel axis whose
// length is the spacing (NRRD `space directions`, the columns of a NIfTI affine), an origin and
// the dims.
//
// Inputs   axes_mm: column c is the step in LPS mm from voxel index c to c+1 (m[row][col]);
//          origin_mm: centre of voxel (0,0,0), LPS; dims >= 0; `name` (the file) for messages.
// Output   spacing = column norms, direction = normalized columns.
// Errors   INVALID_ARGUMENT naming the file when an axis has zero or non-finite length, or the
//          axes are sheared or non-orthogonal beyond what validate_geometry allows (a third axis
//          leaning like a tilted series' k is a sheared grid soiq keeps as it is).
// Cost     O(1); thread-safe.

#include <array>
#include <cstdint>
#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"

namespace soiq {

Result<ImageGeometry> geometry_from_axes(const Mat3& axes_mm, const Vec3& origin_mm, const std::array<int64_t, 3>& dims,
                                         const std::string& name);

}  // namespace soiq
