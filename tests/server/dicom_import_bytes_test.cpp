// The bytes an ImportDicom admits against the memory budget (server/app/dicom_import_bytes.h), from
// header facts only: 12 bytes per voxel of each CT, MR or PT series plus one slice at 4 bytes per
// pixel, counted by hand here.
#include "server/app/dicom_import_bytes.h"

#include <gtest/gtest.h>

#include <string>

#include "core/base/image_geometry.h"

namespace soiq::server {
namespace {

dicom::DicomSeries series(const std::string& uid, const std::string& modality, int64_t rows, int64_t columns,
                          int slices) {
  dicom::DicomSeries s;
  s.series_uid = uid;
  s.modality = modality;
  for (int k = 0; k < slices; ++k) {
    dicom::DicomInstance i;
    i.series_uid = uid;
    i.rows = rows;
    i.columns = columns;
    s.instances.push_back(i);
  }
  return s;
}

TEST(DicomImportBytes, OneCtSeriesCountsSlicesVolumeBlobAndOneStoredSlice) {
  dicom::DicomScan scan;
  scan.series.push_back(series("1.2.3", "CT", 4, 5, 3));
  const DicomImportBytes b = dicom_import_bytes(scan, kDefaultMaxVoxels);
  EXPECT_EQ(b.series, 1);
  EXPECT_EQ(b.bytes, 60 * 12 + 20 * 4);  // 5 x 4 x 3 voxels; one slice of 20 pixels
  EXPECT_EQ(b.what, "importing series 1.2.3 (5x4x3)");
}

TEST(DicomImportBytes, SeriesThatAreNotDecodedCountNothing) {
  dicom::DicomScan scan;
  scan.series.push_back(series("rt", "RTSTRUCT", 0, 0, 1));
  scan.series.push_back(series("seg", "SEG", 512, 512, 1));
  scan.series.push_back(series("cr", "CR", 2048, 2048, 1));
  scan.series.push_back(series("no-rows", "MR", 0, 256, 10));
  scan.series.push_back(series("over-limit", "CT", 100, 100, 11));  // refused before decoding
  const DicomImportBytes b = dicom_import_bytes(scan, 100 * 100 * 10);
  EXPECT_EQ(b.series, 0);
  EXPECT_EQ(b.bytes, 0);
  EXPECT_EQ(b.what, "");
}

TEST(DicomImportBytes, SeveralSeriesAddUpAndTheFirstThreeAreNamed) {
  dicom::DicomScan scan;
  for (const char* uid : {"a", "b", "c", "d", "e"}) scan.series.push_back(series(uid, "PT", 2, 3, 4));
  const DicomImportBytes b = dicom_import_bytes(scan, kDefaultMaxVoxels);
  EXPECT_EQ(b.series, 5);
  EXPECT_EQ(b.bytes, 5 * (24 * 12 + 6 * 4));
  EXPECT_EQ(b.what, "importing 5 series (a 3x2x4, b 3x2x4, c 3x2x4, and 2 more)");
}

}  // namespace
}  // namespace soiq::server
