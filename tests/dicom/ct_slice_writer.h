#pragma once
// Test support: a small CT series written with DCMTK from tests/data/dicom/CT_small.dcm (one
// 128 x 128 signed 16-bit slice, 0.661468 mm pixels, axial), n slices 5 mm apart with their own SOP
// Instance UIDs, each passed through `edit` before it is saved: the way tests make hostile headers
// (a Rows that disagrees with the pixels, an absurd Rescale Slope, a NaN position) on real pixels.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "dicom_test_support.h"

namespace soiq::dicom::testing {

inline constexpr char kSyntheticCtSeriesUid[] = "1.2.826.0.1.3680043.9.7433.2.1";

// edit(dataset, k) runs on slice k before it is saved as "<dir>/ct_<k>.dcm". Returns the paths.
inline std::vector<std::string> write_ct_series(const TempDir& dir, int slices,
                                                const std::function<void(DcmDataset&, int)>& edit = {}) {
  std::vector<std::string> paths;
  for (int k = 0; k < slices; ++k) {
    DcmFileFormat file;
    EXPECT_TRUE(file.loadFile(data_dir("dicom/CT_small.dcm").c_str()).good());
    DcmDataset& ds = *file.getDataset();
    const std::string uid = std::string(kSyntheticCtSeriesUid) + "." + std::to_string(k + 1);
    EXPECT_TRUE(ds.putAndInsertString(DCM_SOPInstanceUID, uid.c_str()).good());
    EXPECT_TRUE(file.getMetaInfo()->putAndInsertString(DCM_MediaStorageSOPInstanceUID, uid.c_str()).good());
    EXPECT_TRUE(ds.putAndInsertString(DCM_SeriesInstanceUID, kSyntheticCtSeriesUid).good());
    EXPECT_TRUE(ds.putAndInsertString(DCM_InstanceNumber, std::to_string(k + 1).c_str()).good());
    const std::string position = "-158.135803\\-179.035797\\" + std::to_string(-75.7 + 5.0 * k);
    EXPECT_TRUE(ds.putAndInsertString(DCM_ImagePositionPatient, position.c_str()).good());
    if (edit) edit(ds, k);
    paths.push_back(dir.file("ct_" + std::to_string(k) + ".dcm"));
    EXPECT_TRUE(file.saveFile(paths.back().c_str(), EXS_LittleEndianExplicit).good()) << paths.back();
  }
  return paths;
}

}  // namespace soiq::dicom::testing
