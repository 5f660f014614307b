#include "server/app/dicom_import_bytes.h"

#include <climits>
#include <utility>
#include <vector>

#include "dicom/import_dicom.h"

namespace soiq::server {
namespace {

constexpr int64_t kBytesPerVoxel = 3 * int64_t(sizeof(float));  // slices, volume, blob
constexpr int64_t kMaxBytesPerStoredPixel = 4;                  // Bits Allocated 32
constexpr size_t kSeriesNamed = 3;

int64_t saturating_add(int64_t a, int64_t b) { return b > INT64_MAX - a ? INT64_MAX : a + b; }

int64_t saturating_mul(int64_t a, int64_t b) { return a != 0 && b > INT64_MAX / a ? INT64_MAX : a * b; }

}  // namespace

DicomImportBytes dicom_import_bytes(const dicom::DicomScan& scan, int64_t max_voxels) {
  DicomImportBytes out;
  std::vector<std::pair<std::string, std::string>> named;  // uid, dims
  for (const dicom::DicomSeries& series : scan.series) {
    if (!dicom::is_volume_modality(series.modality) || series.instances.empty()) continue;
    const dicom::DicomInstance& first = series.instances.front();
    const int64_t slices = int64_t(series.instances.size());
    const int64_t slice_pixels = first.rows * first.columns;  // each at most 65535: no overflow
    const int64_t voxels = saturating_mul(slice_pixels, slices);
    if (voxels == 0 || voxels > max_voxels) continue;
    const int64_t bytes =
        saturating_add(saturating_mul(voxels, kBytesPerVoxel), slice_pixels * kMaxBytesPerStoredPixel);
    out.bytes = saturating_add(out.bytes, bytes);
    ++out.series;
    if (named.size() < kSeriesNamed)
      named.emplace_back(series.series_uid, std::to_string(first.columns) + "x" + std::to_string(first.rows) + "x" +
                                                std::to_string(slices));
  }
  if (out.series == 1) {
    out.what = "importing series " + named[0].first + " (" + named[0].second + ")";
  } else if (out.series > 1) {
    out.what = "importing " + std::to_string(out.series) + " series (";
    for (size_t n = 0; n < named.size(); ++n) out.what += (n ? ", " : "") + named[n].first + " " + named[n].second;
    if (out.series > int(named.size())) out.what += ", and " + std::to_string(out.series - int(named.size())) + " more";
    out.what += ")";
  }
  return out;
}

}  // namespace soiq::server
