#include "core/io/read_image.h"

#include <cctype>

#include "core/io/file_extension.h"
#include "core/io/read_metaimage.h"
#include "core/io/read_nifti.h"
#include "core/io/read_nrrd.h"

namespace soiq {

Result<Image> read_image(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext == ".nii" || ext == ".nii.gz") return read_nifti(path);
  if (ext == ".nrrd" || ext == ".nhdr") return read_nrrd(path);
  if (ext == ".mha" || ext == ".mhd") return read_metaimage(path);
  return invalid_argument("unknown image extension '" + ext + "' of '" + path +
                          "'; soiq reads .nii, .nii.gz, .nrrd, .nhdr, .mha and .mhd");
}

Result<Image> decode_image(const std::string& bytes, const std::string& format, const std::string& name,
                           const ImageDecodeLimits& limits) {
  std::string f = format;
  for (char& c : f) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (f.starts_with(".")) f.erase(0, 1);
  if (f == "nii" || f == "nii.gz") return parse_nifti(bytes, name, limits);
  if (f == "nrrd") return parse_nrrd(bytes, name, std::nullopt, limits);
  if (f == "mha") return parse_metaimage(bytes, name, std::nullopt, limits);
  return invalid_argument("unknown image format '" + format + "' of '" + name + "'; known: nii, nii.gz, nrrd, mha");
}

Mask mask_from_image(const Image& image, int label) {
  Mask mask{image.geometry, std::vector<uint8_t>(image.voxels.size(), 0)};
  // NaN voxels are never inside, whatever the label.
  for (size_t n = 0; n < image.voxels.size(); ++n) {
    const float v = image.voxels[n];
    mask.voxels[n] = label < 0 ? uint8_t(v != 0 && v == v) : uint8_t(double(v) == double(label));
  }
  return mask;
}

}  // namespace soiq
