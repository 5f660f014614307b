// The whole import: every shipped DICOM file read without a crash, and errors that name their cause.
#include "dicom/import_dicom.h"

#include <gtest/gtest.h>

#include "ct_slice_writer.h"
#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;

TEST(ImportDicom, MissingReferencedSeriesIsNotFoundNamingItsUid) {
  auto r = import_dicom({data_dir("dicom/rtstruct.dcm")});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_TRUE(r->structure_sets.empty());
  ASSERT_EQ(r->problems.size(), 1u);
  EXPECT_EQ(r->problems[0].status.code(), StatusCode::kNotFound);
  EXPECT_NE(r->problems[0].status.message().find("1.2.826.0.1.3680043.8.498.2010020400001.2.1.1"), std::string::npos)
      << r->problems[0].status.message();
}

TEST(ImportDicom, EveryShippedFileIsReadAndEveryProblemNamed) {
  auto r = import_dicom({data_dir("dicom"), data_dir("sts/STS_002/dicom")});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  // CT_small, MR_small, the rt-utils CT, STS_002 CT and PET; the DICOMDIR sets' CT and MR series are
  // 16x16 downsized single images or header-only instances, imported or reported.
  EXPECT_NE(r->find_image("1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322"), nullptr);
  EXPECT_NE(r->find_image("1.3.6.1.4.1.5962.1.3.4.1.20040826185059.5457"), nullptr);
  EXPECT_NE(r->find_image("2.16.840.1.114362.1.11940992.23790159890.563423471.893.88"), nullptr);
  EXPECT_EQ(r->structure_sets.size(), 3u + 2u);  // rt-utils' three, STS_002's CT and PET
  for (const auto& p : r->problems) {
    EXPECT_FALSE(p.status.ok());
    EXPECT_FALSE(p.status.message().empty());
  }
  EXPECT_EQ(r->scan.non_dicom_skipped, 10);  // READMEs, licences, facts.json, rtstruct.dump, make_standard_seg.py
}

TEST(ImportDicom, SeriesWithAHostileHeaderIsAProblemNamingTheFileAndYieldsNoImage) {
  testing::TempDir dir;
  testing::write_ct_series(dir, 3, [](DcmDataset& ds, int k) {
    if (k == 2) {
      ASSERT_TRUE(ds.putAndInsertString(DCM_RescaleSlope, "1e308").good());
    }
  });
  auto r = import_dicom({dir.path().string()});
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_TRUE(r->images.empty());
  ASSERT_EQ(r->problems.size(), 1u);
  EXPECT_EQ(r->problems[0].path, testing::kSyntheticCtSeriesUid);
  EXPECT_EQ(r->problems[0].status.code(), StatusCode::kInvalidArgument);
  const std::string& m = r->problems[0].status.message();
  EXPECT_NE(m.find(std::string("series ") + testing::kSyntheticCtSeriesUid + ": '" + dir.file("ct_2.dcm") +
                   "': Rescale Slope (0028,1053) 1e+308"),
            std::string::npos)
      << m;
}

TEST(ImportDicom, MissingPathIsNotFound) {
  auto r = import_dicom({data_dir("dicom/nothing_here")});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace soiq::dicom
