#pragma once
// Reads an image with its full geometry in LPS (docs/DESIGN.md "Coordinates and grids"), by extension:
//   .nii, .nii.gz  NIfTI-1/2 through libnifti (qform when qform_code > 0, else sform, else pixdim),
//                  RAS converted to LPS;
//   .nrrd, .nhdr   NRRD (raw or gzip encoding, `space` LPS/RAS, `space directions`, `space origin`);
//   .mha, .mhd     MetaImage (Offset, TransformMatrix, ElementSpacing, MET_* types, compressed or not).
// Voxel values are converted to float (scl_slope/scl_inter applied for NIfTI).
// Errors  NOT_FOUND missing file; INVALID_ARGUMENT unknown extension, malformed or truncated
//         header/data, non-3D images, sheared or non-orthogonal axes (message names the file).

#include <string>

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/io/image_decode_limits.h"

namespace soiq {

Result<Image> read_image(const std::string& path);

// An image from bytes that are not a local file (an upload): `format` is nii, nii.gz, nrrd or mha
// (a leading '.' and case are ignored), `name` stands for it in messages. Parsed in memory, never
// through a path; a header that names a separate data file (NRRD `data file`, MetaImage
// `ElementDataFile`, a NIfTI .hdr/.img pair) is INVALID_ARGUMENT. `limits` are checked once the
// header is parsed, before any voxel is inflated or decoded (image_decode_limits.h).
Result<Image> decode_image(const std::string& bytes, const std::string& format, const std::string& name,
                           const ImageDecodeLimits& limits = {});

// The voxels equal to `label` (or nonzero when label < 0) as a 0/1 mask on the image's grid.
Mask mask_from_image(const Image& image, int label = -1);

}  // namespace soiq
