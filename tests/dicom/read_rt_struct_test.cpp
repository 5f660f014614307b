// RT Structure Set parsing: the facts tests/data/dicom/README.md and facts.json give for rtstruct.dcm.
#include "dicom/read_rt_struct.h"

#include <gtest/gtest.h>

#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;

TEST(ReadRtStruct, PydicomStructureSetHasThreeRoisAndItsReferences) {
  auto r = read_rt_struct(data_dir("dicom/rtstruct.dcm"));  // a bare dataset: no preamble, no meta
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->patient_id, "tPhantom30sep");
  EXPECT_EQ(r->label, "sep30");
  EXPECT_EQ(r->frame_of_reference_uids, std::vector<std::string>{"1.2.826.0.1.3680043.8.498.2010020400001.2"});
  EXPECT_EQ(r->referenced_series_uids, std::vector<std::string>{"1.2.826.0.1.3680043.8.498.2010020400001.2.1.1"});
  EXPECT_TRUE(r->referenced_image_uids.empty());  // no Contour Image Sequence
  ASSERT_EQ(r->rois.size(), 3u);
  const RtRoi& patient = r->rois[0];
  EXPECT_EQ(patient.number, 1);
  EXPECT_EQ(patient.name, "patient");
  ASSERT_EQ(patient.contours.size(), 3u);
  size_t points = 0;
  for (const auto& c : patient.contours) points += c.points_mm.size();
  EXPECT_EQ(points, 17u);
  EXPECT_EQ(patient.contours[0].points_mm[0][2], -200);
  EXPECT_EQ(patient.contours[2].points_mm[0][2], -180);
  for (int i : {1, 2}) {
    EXPECT_EQ(r->rois[i].name, "Isocenter " + std::to_string(i));
    EXPECT_TRUE(r->rois[i].contours.empty());
    EXPECT_EQ(r->rois[i].other_contours, 1);
    EXPECT_EQ(r->rois[i].other_types, "POINT");
  }
}

TEST(ReadRtStruct, MimStructureSetListsItsContourImages) {
  auto r = read_rt_struct(data_dir("dicom/rt-utils/invalid_reference_rt.dcm"));
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->referenced_series_uids,
            std::vector<std::string>{"2.16.840.1.114362.1.11940992.23790159890.563423471.893.88"});
  EXPECT_EQ(r->referenced_image_uids.size(), 5u);
  ASSERT_EQ(r->rois.size(), 4u);
  for (const auto& roi : r->rois) EXPECT_EQ(roi.contours.size(), 3u) << roi.name;
}

TEST(ReadRtStruct, ImageIsNotAStructureSet) {
  auto r = read_rt_struct(data_dir("dicom/CT_small.dcm"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("not an RT Structure Set"), std::string::npos);
}

}  // namespace
}  // namespace soiq::dicom
