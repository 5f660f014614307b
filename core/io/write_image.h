#pragma once
// Writes a mask (uint8 0/1) or an image (float32) with its full geometry, by extension:
// .nii, .nii.gz (qform and sform, RAS as NIfTI requires), .nrrd (gzip, space LPS), .mha (MetaImage,
// zlib-compressed). Reading back with read_image gives the same geometry and voxels.
// Errors: INVALID_ARGUMENT unknown extension; INTERNAL/NOT_FOUND when the file cannot be written.

#include <string>

#include "core/base/image.h"
#include "core/base/status.h"

namespace soiq {

Status write_mask(const Mask& mask, const std::string& path);
Status write_image(const Image& image, const std::string& path);

}  // namespace soiq
