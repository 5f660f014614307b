// Feeds each input, written to a private temp file, to read_seg_file (dicom/read_seg.h), as an import
// does with a DICOM Segmentation a client sends (dicom/import_seg.cpp), on the grid of
// tests/data/dicom/standard_seg.dcm (11 x 7 x 6 voxels of 0.9 x 1.2 x 3 mm from (10, -5.5, 20) mm),
// so mutations of that seed map frames onto slices and unpack their bits. Through a file because
// read_seg has no in-memory form: DCMTK checks an element's length against a file's size but not
// against a memory buffer's, where it allocates whatever length a header announces.
// DCMTK is not instrumented, so only its crashes show. A bug is any crash or sanitizer report, a run
// over -timeout or -rss_limit_mb (frames x rows x columns must be checked against the Pixel Data
// before anything is allocated for them), or an OK result whose segment volumes are not well-formed
// runs on that grid; any error status is a correct answer.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/base/image_geometry.h"
#include "dicom/read_seg.h"
#include "fuzz/dicom_quiet.h"
#include "fuzz/require.h"
#include "fuzz/temp_input_files.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  soiq::fuzz::quiet_dcmtk();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const soiq::ImageGeometry grid = [] {
    soiq::ImageGeometry g;
    g.origin_mm = {10, -5.5, 20};
    g.spacing_mm = {0.9, 1.2, 3.0};
    g.dims = {11, 7, 6};
    return g;
  }();
  static soiq::fuzz::TempInputFiles files;
  const auto paths = files.write({std::string_view(reinterpret_cast<const char*>(data), size)});
  auto seg = soiq::dicom::read_seg_file(paths.front(), grid);
  if (!seg.ok()) return 0;
  for (const auto& segment : seg->segments) {
    const soiq::RunLengthVolume& v = segment.volume;
    soiq::fuzz::require(v.geometry.dims == grid.dims, "read_seg returned a segment on another grid");
    soiq::fuzz::require(int64_t(v.line_start.size()) == v.line_count() + 1,
                        "read_seg returned a line table of the wrong size");
    for (const soiq::Run& run : v.runs)
      soiq::fuzz::require(0 <= run.begin && run.begin < run.end && run.end <= grid.dims[0],
                          "read_seg returned a run outside its line");
  }
  return 0;
}
