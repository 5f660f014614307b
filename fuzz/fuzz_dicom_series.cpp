// Feeds each input to the DICOM image path of an import, as soiqd runs it on files a client sends:
// the input is split at each "\nSOIQ-NEXT-SLICE\n" into up to 4 files (so slice stacking is reached
// too, not only one slice), scan_dicom reads their headers (dicom/scan_dicom.h), and
// read_image_series (dicom/read_image_series.h) reads them as one series, with the modality the scan
// found (PT, the path with the most checks, when it found none). DCMTK parses the files; it is not
// instrumented, so only its crashes show. A bug is any crash or sanitizer report, a run over
// -timeout or -rss_limit_mb (the voxel cap below must stop a huge announced grid before pixels are
// read), or an OK image whose voxel count is not its grid's.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "dicom/read_image_series.h"
#include "dicom/scan_dicom.h"
#include "fuzz/dicom_quiet.h"
#include "fuzz/require.h"
#include "fuzz/temp_input_files.h"

namespace {

constexpr std::string_view kSliceSeparator = "\nSOIQ-NEXT-SLICE\n";
constexpr size_t kMaxSlices = 4;
constexpr int64_t kMaxVoxels = int64_t(1) << 24;

std::vector<std::string_view> split_slices(std::string_view bytes) {
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < kMaxSlices) {
    const size_t at = bytes.find(kSliceSeparator);
    if (at == std::string_view::npos) break;
    parts.push_back(bytes.substr(0, at));
    bytes.remove_prefix(at + kSliceSeparator.size());
  }
  parts.push_back(bytes);
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  soiq::fuzz::quiet_dcmtk();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static soiq::fuzz::TempInputFiles files;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> paths = files.write(split_slices(bytes));

  soiq::dicom::DicomSeries series;
  series.series_uid = "fuzz-series";
  series.modality = "PT";
  auto scan = soiq::dicom::scan_dicom({files.dir()});
  if (scan.ok() && !scan->series.empty()) series.modality = scan->series.front().modality;
  for (size_t k = 0; k < paths.size(); ++k) series.instances.push_back({paths[k], "", "", "", int64_t(k)});

  auto image = soiq::dicom::read_image_series(series, kMaxVoxels);
  if (image.ok()) {
    soiq::fuzz::require(int64_t(image->image.voxels.size()) == image->image.geometry.voxel_count(),
                        "read_image_series returned a voxel count other than the grid's");
  }
  return 0;
}
