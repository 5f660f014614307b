#pragma once
// Test support for the SEG tests: a synthetic source series, a command runner, and pydicom as an
// independent decoder of SEG files (python3-pydicom and python3-numpy are declared dependencies in
// scripts/install-deps, so a missing pydicom fails the test rather than skipping it). Header-only
// (tests/dicom globs *_test.cpp).

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"

namespace soiq::dicom::testing {

inline SegSource synthetic_source(const ImageGeometry& g) {
  SegSource s;
  s.patient_id = "SEG-TEST-1";
  s.patient_sex = "F";
  s.patient_birth_date = "19700101";
  s.study_uid = "1.2.826.0.1.3680043.8.498.71";
  s.study_date = "20240102";
  s.study_time = "101112";
  s.study_id = "S1";
  s.accession_number = "A42";
  s.series_uid = "1.2.826.0.1.3680043.8.498.72";
  s.frame_of_reference_uid = "1.2.826.0.1.3680043.8.498.73";
  s.modality = "CT";
  s.sop_class_uid = UID_CTImageStorage;
  for (int64_t k = 0; k < g.dims[2]; ++k)
    s.slice_sop_instance_uids.push_back("1.2.826.0.1.3680043.8.498.74." + std::to_string(k + 1));
  s.geometry = g;
  return s;
}

// Runs `command` through the shell, its stdout and stderr captured; the exit status in `status`.
inline std::string run_command(const std::string& command, int& status) {
  std::string out;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    status = -1;
    return "popen failed";
  }
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  status = ::pclose(pipe);
  return out;
}

// A python3 that imports pydicom and numpy: Debian's /usr/bin/python3 (python3-pydicom installs
// there) before whatever python3 the PATH finds first; "" when none does.
inline std::string python_with_pydicom() {
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    int status = 0;
    run_command(std::string(python) + " -c 'import pydicom, numpy'", status);
    if (status == 0) return python;
  }
  return "";
}

// pydicom's decoding (ds.pixel_array) of `seg_path`, as one mask per segment on `grid`: frame f
// of segment s sets the voxels of slice k, where k is the slice its Image Position (Patient) lies
// on. Fails the test (and returns no masks) when pydicom is missing or refuses the file, or a
// frame lies off the grid's slices.
inline std::vector<Mask> pydicom_segments(const std::string& seg_path, const ImageGeometry& grid, size_t segments,
                                          const TempDir& tmp) {
  const std::string python = python_with_pydicom();
  EXPECT_FALSE(python.empty()) << "no python3 with pydicom and numpy: install python3-pydicom python3-numpy "
                                  "(scripts/install-deps)";
  if (python.empty()) return {};
  const std::string script = tmp.file("decode_seg.py"), pixels = tmp.file("pixels.u8"), frames = tmp.file("frames.txt");
  std::ofstream(script) << R"(import sys
import numpy as np
import pydicom
ds = pydicom.dcmread(sys.argv[1])
n, rows, cols = int(ds.NumberOfFrames), int(ds.Rows), int(ds.Columns)
assert int(ds.BitsAllocated) == 1, ds.BitsAllocated
assert len(ds.PixelData) == (n * rows * cols + 7) // 8 + ((n * rows * cols + 7) // 8) % 2, len(ds.PixelData)
ds.pixel_array.reshape(n, rows, cols).astype(np.uint8).tofile(sys.argv[2])
with open(sys.argv[3], "w") as out:
    out.write(f"{n} {rows} {cols}\n")
    for item in ds.PerFrameFunctionalGroupsSequence:
        segment = int(item.SegmentIdentificationSequence[0].ReferencedSegmentNumber)
        p = [float(v) for v in item.PlanePositionSequence[0].ImagePositionPatient]
        out.write(f"{segment} {p[0]!r} {p[1]!r} {p[2]!r}\n")
)";
  int status = 0;
  const std::string log = run_command(python + " " + script + " " + seg_path + " " + pixels + " " + frames, status);
  EXPECT_EQ(status, 0) << "pydicom could not decode " << seg_path << ":\n" << log;
  if (status != 0) return {};

  std::ifstream info(frames);
  int64_t n = 0, rows = 0, cols = 0;
  info >> n >> rows >> cols;
  EXPECT_EQ(rows, grid.dims[1]);
  EXPECT_EQ(cols, grid.dims[0]);
  if (rows != grid.dims[1] || cols != grid.dims[0]) return {};
  std::ifstream in(pixels, std::ios::binary);
  std::vector<char> bits((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(static_cast<int64_t>(bits.size()), n * rows * cols);
  if (static_cast<int64_t>(bits.size()) != n * rows * cols) return {};

  std::vector<Mask> out(segments, Mask{grid, std::vector<uint8_t>(static_cast<size_t>(grid.voxel_count()), 0)});
  const int64_t per_frame = rows * cols;
  for (int64_t f = 0; f < n; ++f) {
    size_t segment = 0;
    Vec3 p{};
    info >> segment >> p[0] >> p[1] >> p[2];
    EXPECT_TRUE(segment >= 1 && segment <= segments) << "frame " << f << " of segment " << segment;
    if (segment < 1 || segment > segments) return {};
    const Vec3 ijk = grid.physical_to_index(p);
    const double k = std::round(ijk[2]);
    // 1e-3 voxel: positions are written as DS values of up to 16 characters.
    const bool on_slice = std::abs(ijk[0]) < 1e-3 && std::abs(ijk[1]) < 1e-3 && std::abs(ijk[2] - k) < 1e-3 && k >= 0 &&
                          k < static_cast<double>(grid.dims[2]);
    EXPECT_TRUE(on_slice) << "frame " << f << " at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    if (!on_slice) return {};
    for (int64_t n2 = 0; n2 < per_frame; ++n2)
      if (bits[static_cast<size_t>(f * per_frame + n2)])
        out[segment - 1].voxels[static_cast<size_t>(static_cast<int64_t>(k) * per_frame + n2)] = 1;
  }
  return out;
}

// Voxel for voxel: `got` (run-length, e.g. our reading) against `want` (pydicom's mask).
inline void expect_same_as_pydicom(const RunLengthVolume& got, const Mask& want, const std::string& what) {
  auto cmp = compare(got, from_mask(want));
  ASSERT_TRUE(cmp.ok()) << cmp.status().to_string();
  EXPECT_GT(cmp->count_b, 0) << what;
  EXPECT_EQ(cmp->only_a, 0) << what << ": voxels ours but not pydicom's";
  EXPECT_EQ(cmp->only_b, 0) << what << ": voxels pydicom's but not ours";
}

}  // namespace soiq::dicom::testing
