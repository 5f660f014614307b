#pragma once
// Test support: writes a minimal RT Structure Set with DCMTK (one ROI, CLOSED_PLANAR contours given
// as LPS points), to test conversion on contours whose answer is a hand count.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "core/base/vec3.h"

namespace soiq::dicom::testing {

inline void write_rt_struct(const std::string& path, const std::string& roi_name,
                            const std::vector<std::vector<Vec3>>& contours,
                            const std::string& referenced_series_uid = "1.2.3.4.5.6") {
  DcmFileFormat file;
  DcmDataset& ds = *file.getDataset();
  ASSERT_TRUE(ds.putAndInsertString(DCM_SOPClassUID, UID_RTStructureSetStorage).good());
  ASSERT_TRUE(ds.putAndInsertString(DCM_SOPInstanceUID, "1.2.3.4.9.1").good());
  ASSERT_TRUE(ds.putAndInsertString(DCM_Modality, "RTSTRUCT").good());
  ASSERT_TRUE(ds.putAndInsertString(DCM_PatientID, "SYNTH").good());
  ASSERT_TRUE(ds.putAndInsertString(DCM_StudyInstanceUID, "1.2.3.4.9.2").good());
  ASSERT_TRUE(ds.putAndInsertString(DCM_SeriesInstanceUID, "1.2.3.4.9.3").good());
  DcmItem* frame = nullptr;
  ASSERT_TRUE(ds.findOrCreateSequenceItem(DCM_ReferencedFrameOfReferenceSequence, frame).good());
  DcmItem *study = nullptr, *series = nullptr;
  ASSERT_TRUE(frame->findOrCreateSequenceItem(DCM_RTReferencedStudySequence, study).good());
  ASSERT_TRUE(study->findOrCreateSequenceItem(DCM_RTReferencedSeriesSequence, series).good());
  ASSERT_TRUE(series->putAndInsertString(DCM_SeriesInstanceUID, referenced_series_uid.c_str()).good());
  DcmItem* roi = nullptr;
  ASSERT_TRUE(ds.findOrCreateSequenceItem(DCM_StructureSetROISequence, roi).good());
  ASSERT_TRUE(roi->putAndInsertString(DCM_ROINumber, "7").good());
  ASSERT_TRUE(roi->putAndInsertString(DCM_ROIName, roi_name.c_str()).good());
  DcmItem* roi_contour = nullptr;
  ASSERT_TRUE(ds.findOrCreateSequenceItem(DCM_ROIContourSequence, roi_contour).good());
  ASSERT_TRUE(roi_contour->putAndInsertString(DCM_ReferencedROINumber, "7").good());
  for (size_t c = 0; c < contours.size(); ++c) {
    DcmItem* item = nullptr;
    ASSERT_TRUE(roi_contour->findOrCreateSequenceItem(DCM_ContourSequence, item, static_cast<long>(c)).good());
    std::ostringstream data;
    data.precision(17);
    for (size_t p = 0; p < contours[c].size(); ++p)
      data << (p ? "\\" : "") << contours[c][p][0] << "\\" << contours[c][p][1] << "\\" << contours[c][p][2];
    ASSERT_TRUE(item->putAndInsertString(DCM_ContourGeometricType, "CLOSED_PLANAR").good());
    ASSERT_TRUE(item->putAndInsertString(DCM_NumberOfContourPoints, std::to_string(contours[c].size()).c_str()).good());
    ASSERT_TRUE(item->putAndInsertString(DCM_ContourData, data.str().c_str()).good());
  }
  ASSERT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
}

}  // namespace soiq::dicom::testing
