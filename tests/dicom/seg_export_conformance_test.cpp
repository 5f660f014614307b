// DICOM SEG export (dicom/seg_export.h) judged by others: pydicom decodes what we write to exactly
// the voxels we wrote (frames of every size residue mod 8, and the GTVs of the real STS series),
// and dicom3tools' dciodvfy finds no error and no warning in it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/base/run_length_volume.h"
#include "dicom/import_dicom.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_source_of.h"
#include "seg_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::TempDir;

// Two segments of pseudo-random voxels (about 40% set) on `g`, slice 1 left empty in the first and
// slice 2 in the second so that frames are sparse and the two segments have different frame counts.
std::vector<SegSegment> two_segments(const ImageGeometry& g) {
  std::vector<SegSegment> out(2);
  uint32_t x = static_cast<uint32_t>(g.dims[0] * 131 + g.dims[1]);
  for (size_t s = 0; s < 2; ++s) {
    Mask m{g, std::vector<uint8_t>(static_cast<size_t>(g.voxel_count()), 0)};
    const int64_t per_slice = g.dims[0] * g.dims[1];
    for (size_t n = 0; n < m.voxels.size(); ++n) {
      x = x * 1664525u + 1013904223u;
      if (static_cast<int64_t>(n) / per_slice != static_cast<int64_t>(s) + 1 && (x >> 24) < 102) m.voxels[n] = 1;
    }
    out[s].label = s == 0 ? "first" : "second";
    out[s].volume = from_mask(m);
  }
  return out;
}

struct FrameSize {
  int64_t columns, rows;
};

class SegExportPydicom : public ::testing::TestWithParam<FrameSize> {};

TEST_P(SegExportPydicom, DecodesToExactlyTheVoxelsWritten) {
  ImageGeometry g;
  g.dims = {GetParam().columns, GetParam().rows, 5};
  g.spacing_mm = {0.8, 1.1, 2.0};
  g.origin_mm = {-20.5, 10.25, 3.0};
  const std::vector<SegSegment> segments = two_segments(g);
  auto written = write_seg(testing::synthetic_source(g), segments);
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  const std::string path = tmp.file("seg.dcm");
  std::ofstream(path, std::ios::binary) << written->bytes;
  const std::vector<Mask> decoded = testing::pydicom_segments(path, g, segments.size(), tmp);
  ASSERT_EQ(decoded.size(), segments.size());
  for (size_t s = 0; s < segments.size(); ++s)
    testing::expect_same_as_pydicom(segments[s].volume, decoded[s], segments[s].label);
}

// rows x columns mod 8 = 0, 1, ..., 7 in this order.
INSTANTIATE_TEST_SUITE_P(AllResidues, SegExportPydicom,
                         ::testing::Values(FrameSize{6, 4}, FrameSize{7, 7}, FrameSize{10, 9}, FrameSize{11, 9},
                                           FrameSize{13, 12}, FrameSize{13, 9}, FrameSize{11, 10}, FrameSize{15, 9}),
                         [](const auto& info) {
                           return std::to_string(info.param.rows) + "x" + std::to_string(info.param.columns);
                         });

struct StsCase {
  std::string patient, modality;  // modality folder: CT, MR_T1, PET
};

void PrintTo(const StsCase& c, std::ostream* os) { *os << c.patient << "/" << c.modality; }

std::string sts_dir(const StsCase& c) {
  const std::string plain = data_dir("sts/" + c.patient + "/dicom/" + c.modality);
  if (std::filesystem::exists(plain)) return plain;
  return data_dir("sts/" + c.patient + "/dicom_jpegls/" + c.modality);
}

// The series' GTV (its RT Structure Set on its grid) as a SEG on the series, and its source.
struct StsSeg {
  SegSource source;
  SegSegment gtv;
};

StsSeg sts_seg(const StsCase& c) {
  StsSeg out;
  auto imported = import_dicom({sts_dir(c)});
  EXPECT_TRUE(imported.ok()) << imported.status().to_string();
  if (!imported.ok() || imported->structure_sets.size() != 1) {
    ADD_FAILURE() << c.patient << "/" << c.modality << ": no RT Structure Set imported";
    return out;
  }
  const ImportedStructureSet& set = imported->structure_sets[0];
  auto source = testing::seg_source_of(*imported, set.referenced_series_uid);
  EXPECT_TRUE(source.ok()) << source.status().to_string();
  if (!source.ok()) return out;
  out.source = *source;
  out.gtv.label = set.converted.structures.at(0).name;
  out.gtv.volume = set.converted.structures.at(0).volume;
  out.gtv.category = {"49755003", "SCT", "Morphologically Altered Structure"};
  out.gtv.type = {"4147007", "SCT", "Mass"};
  return out;
}

class SegExportStsPydicom : public ::testing::TestWithParam<StsCase> {};

TEST_P(SegExportStsPydicom, GtvDecodesToExactlyItsVoxels) {
  const StsSeg in = sts_seg(GetParam());
  ASSERT_FALSE(in.gtv.label.empty());
  auto written = write_seg(in.source, {in.gtv});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  const std::string path = tmp.file("gtv.dcm");
  std::ofstream(path, std::ios::binary) << written->bytes;
  const std::vector<Mask> decoded = testing::pydicom_segments(path, in.source.geometry, 1, tmp);
  ASSERT_EQ(decoded.size(), 1u);
  testing::expect_same_as_pydicom(in.gtv.volume, decoded[0], in.gtv.label);
}

std::vector<StsCase> sts_cases() {
  std::vector<StsCase> out;
  for (const char* p : {"STS_002", "STS_008", "STS_012", "STS_025"})
    for (const char* m : {"CT", "MR_T1", "PET"}) out.push_back({p, m});
  return out;
}

INSTANTIATE_TEST_SUITE_P(Sts, SegExportStsPydicom, ::testing::ValuesIn(sts_cases()),
                         [](const auto& info) { return info.param.patient + "_" + info.param.modality; });

// dciodvfy's findings on `path`: its "Error" and "Warning" lines.
std::vector<std::string> dciodvfy_findings(const std::string& path, std::string& all) {
  int status = 0;
  all = testing::run_command("dciodvfy " + path, status);
  EXPECT_NE(all.find("Segmentation"), std::string::npos)
      << "dciodvfy did not run (apt-get install dicom3tools; scripts/install-deps):\n"
      << all;
  std::vector<std::string> out;
  std::istringstream lines(all);
  for (std::string line; std::getline(lines, line);)
    if (line.find("Error") != std::string::npos || line.find("Warning") != std::string::npos) out.push_back(line);
  return out;
}

TEST(SegExportDciodvfy, SyntheticTwoSegmentSegHasNoErrorOrWarning) {
  ImageGeometry g;
  g.dims = {13, 9, 5};
  g.spacing_mm = {0.8, 1.1, 2.0};
  g.origin_mm = {-20.5, 10.25, 3.0};
  std::vector<SegSegment> segments = two_segments(g);
  segments[0].display_rgb = std::array<uint8_t, 3>{255, 0, 0};
  segments[1].algorithm_type = SegAlgorithmType::kManual;
  auto written = write_seg(testing::synthetic_source(g), segments);
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  const std::string path = tmp.file("seg.dcm");
  std::ofstream(path, std::ios::binary) << written->bytes;
  std::string all;
  for (const std::string& f : dciodvfy_findings(path, all)) ADD_FAILURE() << f;
  if (HasFailure()) std::cout << all;
}

// STS_002's CT has the 17-character Study ID "IBSI_1_STS_002_CT" where SH allows 16: the SEG writes
// it empty (Type 2, seg_export.h), which dciodvfy accepts with one advisory warning that a DICOMDIR
// would need it. That warning, and only it, is tolerated here.
TEST(SegExportDciodvfy, StsGtvSegHasNoErrorOrWarningButTheDicomdirStudyIdOne) {
  const StsSeg in = sts_seg({"STS_002", "CT"});
  ASSERT_FALSE(in.gtv.label.empty());
  ASSERT_GT(in.source.study_id.size(), 16u) << "the source's Study ID now fits SH: drop the tolerance below";
  auto written = write_seg(in.source, {in.gtv});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  const std::string path = tmp.file("gtv.dcm");
  std::ofstream(path, std::ios::binary) << written->bytes;
  std::string all;
  for (const std::string& f : dciodvfy_findings(path, all))
    if (f != "Warning - Missing attribute or value that would be needed to build DICOMDIR - Study ID")
      ADD_FAILURE() << f;
  if (HasFailure()) std::cout << all;
}

}  // namespace
}  // namespace soiq::dicom
