// Feeds each input, written to a private temp file, to read_rt_struct (dicom/read_rt_struct.h) and
// converts what it returns with convert_rt_struct (dicom/convert_rt_struct.h), as an import does with
// an RT Structure Set a client sends. The grid stands in for the referenced series: axis-aligned, up
// to 64 x 64 x 64 voxels around the contours' points, slices on the first contour's plane and the
// next distinct one, so contours land on it and reach fill_contours and marching cubes; when a
// coordinate is beyond 1e5 mm (no scanner's), a fixed 64 mm cube at the origin, so that absurd
// contours meet a real grid. DCMTK parses the file; it is not instrumented, so only its crashes
// show. A bug is any crash or sanitizer report, or a run over -timeout or -rss_limit_mb; any error
// status is a correct answer.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string_view>

#include "core/base/image_geometry.h"
#include "dicom/convert_rt_struct.h"
#include "dicom/read_rt_struct.h"
#include "fuzz/dicom_quiet.h"
#include "fuzz/temp_input_files.h"

namespace {

constexpr int64_t kGridSide = 64;
constexpr double kFarMm = 1e5;

soiq::ImageGeometry grid_around_contours(const soiq::dicom::RtStructureSet& rs) {
  soiq::ImageGeometry fixed;
  fixed.dims = {kGridSide, kGridSide, kGridSide};
  soiq::Vec3 lo{kFarMm, kFarMm, kFarMm}, hi{-kFarMm, -kFarMm, -kFarMm};
  std::set<double> planes;
  for (const auto& roi : rs.rois) {
    for (const auto& contour : roi.contours) {
      for (const auto& p : contour.points_mm) {
        for (int a = 0; a < 3; ++a) {
          if (!(std::abs(p[a]) <= kFarMm)) return fixed;  // NaN too
          lo[a] = std::min(lo[a], p[a]);
          hi[a] = std::max(hi[a], p[a]);
        }
      }
      if (!contour.points_mm.empty() && planes.size() < 2) planes.insert(contour.points_mm.front()[2]);
    }
  }
  if (planes.empty()) return fixed;
  soiq::ImageGeometry g;
  g.origin_mm = {lo[0], lo[1], *planes.begin()};
  for (int a = 0; a < 2; ++a) g.spacing_mm[a] = std::max((hi[a] - lo[a]) / double(kGridSide - 1), 0.01);
  g.spacing_mm[2] = planes.size() == 2 ? std::max(*planes.rbegin() - *planes.begin(), 0.01) : 1.0;
  g.dims = {kGridSide, kGridSide, kGridSide};
  return g;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  soiq::fuzz::quiet_dcmtk();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static soiq::fuzz::TempInputFiles files;
  const auto paths = files.write({std::string_view(reinterpret_cast<const char*>(data), size)});
  auto rs = soiq::dicom::read_rt_struct(paths.front());
  if (!rs.ok()) return 0;
  const soiq::ImageGeometry grid = grid_around_contours(*rs);
  if (!soiq::validate_geometry(grid).ok()) return 0;
  (void)soiq::dicom::convert_rt_struct(*rs, grid, kGridSide * kGridSide * kGridSide);
  return 0;
}
