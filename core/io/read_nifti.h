#pragma once
// Reads a 3D single-file NIfTI-1 or NIfTI-2 image (.nii, .nii.gz) from memory; the NIfTI branch
// of read_image (see read_image.h for the shared contract). The header is checked here (sizeof_hdr,
// magic n+1/n+2, dim[], vox_offset against the bytes there are) before libnifti turns it into
// matrices, and the voxels are decoded by soiq, so libnifti never opens a file: a two-file
// .hdr/.img header is refused rather than followed to its companion.
//
// Geometry   the qform when qform_code > 0, else the sform when sform_code > 0, else the pixdim
//            diagonal (NIfTI "method 1"); NIfTI's RAS world is turned to LPS by negating the first
//            two rows of the affine. Spacing = column norms, direction = normalized columns.
// Voxels     uint8, int8, uint16, int16, uint32, int32, float32, float64, as float, with
//            value * scl_slope + scl_inter applied when scl_slope is finite and nonzero.
// Errors     NOT_FOUND missing file; INVALID_ARGUMENT unreadable or two-file header, vox_offset
//            inside the header or past the data, truncated data, more than 3 dimensions of size
//            > 1, unsupported datatype, sheared axes, scaling beyond float; RESOURCE_EXHAUSTED more
//            than kDefaultMaxVoxels voxels (checked before the data is inflated or decoded).
// Cost       O(voxels). Thread-safety: libnifti keeps global options; soiq only ever sets its
//            debug level to 0, so concurrent reads are safe in practice.

#include <string>
#include <string_view>

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/io/image_decode_limits.h"

namespace soiq {

Result<Image> read_nifti(const std::string& path);
// The same from the file's bytes (gzip-compressed or not); `name` stands for the file in messages.
Result<Image> parse_nifti(std::string_view bytes, const std::string& name, const ImageDecodeLimits& limits);

}  // namespace soiq
