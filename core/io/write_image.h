#pragma once
// Writes a mask (uint8 0/1) or an image (float32) with its full geometry, by extension:
// .nii, .nii.gz (qform and sform, RAS as NIfTI requires), .nrrd (gzip, space LPS), .mha (MetaImage,
// zlib-compressed). Reading back with read_image gives the same geometry and voxels.
// Errors: INVALID_ARGUMENT unknown extension; INTERNAL/NOT_FOUND when the file cannot be written;
// FAILED_PRECONDITION for a grid with unevenly spaced slices (check_evenly_spaced), which these
// formats cannot hold: writing it as if even would put voxels where the series has none.

#include <string>

#include "core/base/image.h"
#include "core/base/status.h"

namespace soiq {

Status write_mask(const Mask& mask, const std::string& path);
// OK unless `g` has unevenly spaced slices; then FAILED_PRECONDITION "cannot write <what>: ..."
// saying what to do instead.
Status check_evenly_spaced(const ImageGeometry& g, const std::string& what);
Status write_image(const Image& image, const std::string& path);

}  // namespace soiq
