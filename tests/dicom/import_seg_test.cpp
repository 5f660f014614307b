// DICOM SEG files import as structures on the series they reference (dicom/import_seg.h): the STS_002
// GTV written as a SEG by soiq and imported with its CT gives the RT Structure Set's voxels back
// exactly; a SEG whose series is missing, whose frame of reference differs, or whose segments are
// empty is reported, not imported.

#include "dicom/import_seg.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/run_length_volume.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_source_of.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::TempDir;
namespace fs = std::filesystem;

struct Fixture {
  DicomImport ct;       // STS_002's CT with its RT Structure Set
  SegSource source;     // of the CT series
  RunLengthVolume gtv;  // the RT Structure Set's GTV on the CT grid
};

Fixture sts_ct() {
  Fixture f;
  auto imported = import_dicom({data_dir("sts/STS_002/dicom/CT")});
  EXPECT_TRUE(imported.ok()) << imported.status().to_string();
  f.ct = std::move(imported).value();
  const ImportedStructureSet& set = f.ct.structure_sets.at(0);
  auto source = testing::seg_source_of(f.ct, set.referenced_series_uid);
  EXPECT_TRUE(source.ok()) << source.status().to_string();
  f.source = *source;
  f.gtv = set.converted.structures.at(0).volume;
  return f;
}

// The CT images (not the RT Structure Set) and `seg` in one folder.
std::string folder_with(const TempDir& tmp, const std::string& seg_bytes) {
  const fs::path dir = tmp.path() / "study";
  fs::create_directories(dir);
  fs::copy(data_dir("sts/STS_002/dicom/CT/image"), dir / "image", fs::copy_options::recursive);
  std::ofstream(dir / "seg.dcm", std::ios::binary) << seg_bytes;
  return dir.string();
}

SegSegment segment(const std::string& label, RunLengthVolume v) {
  SegSegment s;
  s.label = label;
  s.volume = std::move(v);
  return s;
}

TEST(ImportSeg, SoiqsOwnSegOfTheStsGtvImportsWithExactlyItsVoxels) {
  const Fixture f = sts_ct();
  SegWriteOptions options;
  options.series_description = "GTV by soiq";
  auto written = write_seg(f.source, {segment("GTV_from_SEG", f.gtv)}, options);
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  auto imported = import_dicom({folder_with(tmp, written->bytes)});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  for (const auto& p : imported->problems) ADD_FAILURE() << p.status.to_string();
  ASSERT_EQ(imported->structure_sets.size(), 1u);  // the SEG; the RT Structure Set was left out
  const ImportedStructureSet& set = imported->structure_sets[0];
  EXPECT_EQ(set.sop_instance_uid, written->sop_instance_uid);
  EXPECT_EQ(set.series_uid, written->series_uid);
  EXPECT_EQ(set.referenced_series_uid, f.source.series_uid);
  EXPECT_EQ(set.label, "GTV by soiq");
  ASSERT_EQ(set.converted.structures.size(), 1u);
  const ImportedStructure& s = set.converted.structures[0];
  EXPECT_EQ(s.name, "GTV_from_SEG");
  EXPECT_EQ(s.roi_number, 1);
  auto same = compare(s.volume, f.gtv);
  ASSERT_TRUE(same.ok()) << same.status().to_string();
  EXPECT_EQ(same->only_a + same->only_b, 0);
  EXPECT_EQ(same->count_a, 17090);
  EXPECT_FALSE(s.surface.triangles.empty());
}

TEST(ImportSeg, SegWhoseSeriesIsNotSentIsNotFoundNamingTheSeries) {
  const Fixture f = sts_ct();
  auto written = write_seg(f.source, {segment("GTV", f.gtv)});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  const fs::path alone = tmp.path() / "alone";
  fs::create_directories(alone);
  std::ofstream(alone / "seg.dcm", std::ios::binary) << written->bytes;
  auto imported = import_dicom({alone.string()});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  EXPECT_TRUE(imported->structure_sets.empty());
  ASSERT_EQ(imported->problems.size(), 1u);
  EXPECT_EQ(imported->problems[0].status.code(), StatusCode::kNotFound);
  EXPECT_NE(imported->problems[0].status.message().find(f.source.series_uid), std::string::npos)
      << imported->problems[0].status.message();
}

TEST(ImportSeg, SegInAnotherFrameOfReferenceIsRefused) {
  Fixture f = sts_ct();
  f.source.frame_of_reference_uid = "1.2.3.4.5";  // the SEG claims other coordinates
  auto written = write_seg(f.source, {segment("GTV", f.gtv)});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  auto imported = import_dicom({folder_with(tmp, written->bytes)});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  EXPECT_TRUE(imported->structure_sets.empty());
  ASSERT_EQ(imported->problems.size(), 1u);
  EXPECT_EQ(imported->problems[0].status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(imported->problems[0].status.message().find("frame of reference 1.2.3.4.5"), std::string::npos)
      << imported->problems[0].status.message();
}

TEST(ImportSeg, TwoSegmentsBecomeTwoStructuresInFileOrder) {
  const Fixture f = sts_ct();
  // The GTV and the same GTV cut to its lower half of slices: two distinct volumes.
  RunLengthVolume lower = f.gtv;
  const int64_t ny = lower.geometry.dims[1], nz = lower.geometry.dims[2];
  std::vector<soiq::Run> runs;
  std::vector<int64_t> starts = {0};
  for (int64_t l = 0; l < ny * nz; ++l) {
    if (l / ny < nz / 2 + 6)
      for (int64_t r = lower.line_start[l]; r < lower.line_start[l + 1]; ++r) runs.push_back(lower.runs[r]);
    starts.push_back(int64_t(runs.size()));
  }
  lower.runs = runs;
  lower.line_start = starts;
  ASSERT_GT(voxel_count(lower), 0);
  ASSERT_LT(voxel_count(lower), voxel_count(f.gtv));
  auto written = write_seg(f.source, {segment("whole", f.gtv), segment("lower", lower)});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  auto imported = import_dicom({folder_with(tmp, written->bytes)});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  ASSERT_EQ(imported->structure_sets.size(), 1u);
  const auto& structures = imported->structure_sets[0].converted.structures;
  ASSERT_EQ(structures.size(), 2u);
  EXPECT_EQ(structures[0].name, "whole");
  EXPECT_EQ(structures[1].name, "lower");
  EXPECT_EQ(structures[1].roi_number, 2);
  EXPECT_EQ(voxel_count(structures[0].volume), voxel_count(f.gtv));
  EXPECT_EQ(voxel_count(structures[1].volume), voxel_count(lower));
}

// A SEG whose Pixel Data was cut short is reported and imports nothing: no structure set that could
// replace a stored structure with a half-read one.
TEST(ImportSeg, TruncatedSegIsInvalidArgumentAndImportsNothing) {
  const Fixture f = sts_ct();
  auto written = write_seg(f.source, {segment("GTV", f.gtv)});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  const std::string dir = folder_with(tmp, written->bytes);
  const std::string seg_path = (fs::path(dir) / "seg.dcm").string();
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(seg_path.c_str()).good());
  DcmDataset& ds = *file.getDataset();
  const Uint8* bytes = nullptr;
  unsigned long count = 0;
  ASSERT_TRUE(ds.findAndGetUint8Array(DCM_PixelData, bytes, &count).good());
  const std::vector<Uint8> half(bytes, bytes + count / 4 * 2);
  ASSERT_TRUE(ds.putAndInsertUint8Array(DCM_PixelData, half.data(), static_cast<unsigned long>(half.size())).good());
  ASSERT_TRUE(file.saveFile(seg_path.c_str(), EXS_LittleEndianExplicit).good());

  auto imported = import_dicom({dir});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  EXPECT_TRUE(imported->structure_sets.empty());
  ASSERT_EQ(imported->problems.size(), 1u);
  const Status& problem = imported->problems[0].status;
  EXPECT_EQ(problem.code(), StatusCode::kInvalidArgument) << problem.to_string();
  EXPECT_NE(problem.message().find("SEG '" + seg_path + "' is truncated: " + std::to_string(half.size()) +
                                   " bytes of pixel data"),
            std::string::npos)
      << problem.to_string();
}

}  // namespace
}  // namespace soiq::dicom
