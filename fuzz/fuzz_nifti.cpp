// Feeds each input to decode_image (core/io/read_image.h) as a .nii upload, as soiqd does with an
// image a client sends: NIfTI-1 or -2, gzip-compressed or not (the reader tells by the bytes, so .nii and .nii.gz are
// one harness and one corpus), header through soiq's checks, then libnifti. Decoded under soiqd-like limits
// (fuzz/image_contract.h). A bug is any crash or sanitizer report, a run over -timeout or
// -rss_limit_mb, or an OK image that breaks decode_image's contract; any error status is a correct
// answer.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/read_image.h"
#include "fuzz/image_contract.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  auto image = soiq::decode_image(bytes, "nii", "fuzz.nii", soiq::fuzz::image_fuzz_limits());
  if (image.ok()) soiq::fuzz::check_image_contract(*image);
  return 0;
}
