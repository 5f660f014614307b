#pragma once
// Reads a 3D NIfTI-1 or NIfTI-2 image (.nii, .nii.gz) through libnifti; the NIfTI branch of
// read_image (see read_image.h for the shared contract).
//
// Geometry   the qform when qform_code > 0, else the sform when sform_code > 0, else the pixdim
//            diagonal (NIfTI "method 1"); NIfTI's RAS world is turned to LPS by negating the first
//            two rows of the affine. Spacing = column norms, direction = normalized columns.
// Voxels     uint8, int8, uint16, int16, uint32, int32, float32, float64, as float, with
//            value * scl_slope + scl_inter applied when scl_slope is finite and nonzero.
// Errors     NOT_FOUND missing file; INVALID_ARGUMENT unreadable header, truncated data, more than
//            3 dimensions of size > 1, unsupported datatype, sheared axes; RESOURCE_EXHAUSTED more
//            than kDefaultMaxVoxels voxels.
// Cost       O(voxels). Thread-safety: libnifti keeps global options; soiq only ever sets its
//            debug level to 0, so concurrent reads are safe in practice.

#include <string>

#include "core/image.h"
#include "core/status.h"

namespace soiq {

Result<Image> read_nifti(const std::string& path);

}  // namespace soiq
