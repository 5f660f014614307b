// Scanning files, folders and DICOMDIRs: the facts tests/data/dicom/README.md and facts.json state.
#include "dicom/scan_dicom.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::TempDir;
namespace fs = std::filesystem;

DicomScan scan(const std::vector<std::string>& paths) {
  auto r = scan_dicom(paths);
  EXPECT_TRUE(r.ok()) << r.status().to_string();
  return r.ok() ? std::move(r).value() : DicomScan{};
}

TEST(ScanDicom, CtSmallGivesItsPatientStudyAndSeries) {
  const DicomScan s = scan({data_dir("dicom/CT_small.dcm")});
  ASSERT_EQ(s.files_read, 1);
  ASSERT_EQ(s.patients.size(), 1u);
  EXPECT_EQ(s.patients[0].patient_id, "1CT1");
  EXPECT_EQ(s.patients[0].sex, "O");
  EXPECT_EQ(s.patients[0].birth_date, "");
  ASSERT_EQ(s.studies.size(), 1u);
  EXPECT_EQ(s.studies[0].study_uid, "1.3.6.1.4.1.5962.1.2.1.20040119072730.12322");
  EXPECT_EQ(s.studies[0].study_date, "20040119");
  EXPECT_EQ(s.studies[0].study_time, "072730");
  EXPECT_EQ(s.studies[0].description, "e+1");
  EXPECT_EQ(s.studies[0].study_id, "1CT1");
  ASSERT_TRUE(s.studies[0].age_years.has_value());  // Patient's Age "000Y", taken as written
  EXPECT_EQ(*s.studies[0].age_years, 0.0);
  ASSERT_EQ(s.series.size(), 1u);
  EXPECT_EQ(s.series[0].series_uid, "1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322");
  EXPECT_EQ(s.series[0].modality, "CT");
  EXPECT_EQ(s.series[0].frame_of_reference_uid, "1.3.6.1.4.1.5962.1.4.1.1.20040119072730.12322");
  EXPECT_EQ(s.series[0].series_number, 1);
  ASSERT_EQ(s.series[0].instances.size(), 1u);
  EXPECT_EQ(s.series[0].instances[0].sop_instance_uid, "1.3.6.1.4.1.5962.1.1.1.1.1.20040119072730.12322");
  EXPECT_EQ(s.series[0].instances[0].sop_class_uid, "1.2.840.10008.5.1.4.1.1.2");
  EXPECT_EQ(s.series[0].instances[0].rows, 128);  // from the header: no pixel read
  EXPECT_EQ(s.series[0].instances[0].columns, 128);
}

TEST(ScanDicom, MrSmallGivesItsPatientStudyAndSeries) {
  const DicomScan s = scan({data_dir("dicom/MR_small.dcm")});
  ASSERT_EQ(s.patients.size(), 1u);
  EXPECT_EQ(s.patients[0].patient_id, "4MR1");
  EXPECT_EQ(s.patients[0].sex, "F");
  ASSERT_EQ(s.studies.size(), 1u);
  EXPECT_EQ(s.studies[0].study_date, "20040826");
  EXPECT_EQ(s.studies[0].study_uid, "1.3.6.1.4.1.5962.1.2.4.20040826185059.5457");
  ASSERT_EQ(s.series.size(), 1u);
  EXPECT_EQ(s.series[0].modality, "MR");
  EXPECT_EQ(s.series[0].frame_of_reference_uid, "1.3.6.1.4.1.5962.1.4.4.1.20040826185059.5457");
}

TEST(ScanDicom, BareDatasetWithoutPreambleOrMetaHeaderIsRead) {
  // rtstruct.dcm: no preamble, no "DICM", no group 0002, Implicit VR LE.
  const DicomScan s = scan({data_dir("dicom/rtstruct.dcm")});
  EXPECT_TRUE(s.unreadable.empty());
  ASSERT_EQ(s.files_read, 1);
  ASSERT_EQ(s.patients.size(), 1u);
  EXPECT_EQ(s.patients[0].patient_id, "tPhantom30sep");
  EXPECT_EQ(s.patients[0].sex, "M");
  EXPECT_EQ(s.patients[0].birth_date, "19691231");
  ASSERT_EQ(s.studies.size(), 1u);
  EXPECT_EQ(s.studies[0].study_uid, "1.2.826.0.1.3680043.8.498.2010020400001.1");
  EXPECT_EQ(s.studies[0].study_date, "");
  EXPECT_EQ(s.studies[0].accession_number, "1");
  EXPECT_EQ(s.studies[0].study_id, "sep30");
  ASSERT_EQ(s.series.size(), 1u);
  EXPECT_EQ(s.series[0].modality, "RTSTRUCT");
}

// A name in the file's own character set is given in UTF-8; one that is not what its character set
// says is left out rather than given garbled.
TEST(ScanDicom, PatientNamesAreGivenInUtf8) {
  TempDir tmp;
  auto write = [&](const std::string& file, const char* charset, const char* name) -> std::string {
    DcmFileFormat f;
    DcmDataset& ds = *f.getDataset();
    if (charset != nullptr) ds.putAndInsertString(DCM_SpecificCharacterSet, charset);
    ds.putAndInsertString(DCM_PatientName, name);
    ds.putAndInsertString(DCM_PatientID, file.c_str());
    ds.putAndInsertString(DCM_SOPClassUID, UID_CTImageStorage);
    ds.putAndInsertString(DCM_SOPInstanceUID, ("1.2.3." + std::to_string(file.size()) + ".1").c_str());
    ds.putAndInsertString(DCM_StudyInstanceUID, ("1.2.3." + file).c_str());
    ds.putAndInsertString(DCM_SeriesInstanceUID, ("1.2.3." + file + ".1").c_str());
    ds.putAndInsertString(DCM_Modality, "CT");
    EXPECT_TRUE(f.saveFile(tmp.file(file).c_str(), EXS_LittleEndianExplicit).good());
    return tmp.file(file);
  };
  const DicomScan latin1 = scan(std::vector<std::string>{write("1", "ISO_IR 100", "M\xFCller^J\xFCrgen")});
  ASSERT_EQ(latin1.patients.size(), 1u);
  EXPECT_EQ(latin1.patients[0].name, "M\xC3\xBCller^J\xC3\xBCrgen");
  const DicomScan utf8 =
      scan(std::vector<std::string>{write("22", "ISO_IR 192", "\xE5\xB1\xB1\xE7\x94\xB0^\xE5\xA4\xAA\xE9\x83\x8E")});
  ASSERT_EQ(utf8.patients.size(), 1u);
  EXPECT_EQ(utf8.patients[0].name, "\xE5\xB1\xB1\xE7\x94\xB0^\xE5\xA4\xAA\xE9\x83\x8E");
  // No character set is ASCII: a Latin-1 byte there is not UTF-8.
  const DicomScan bad = scan(std::vector<std::string>{write("333", nullptr, "M\xFCller")});
  ASSERT_EQ(bad.patients.size(), 1u);
  EXPECT_EQ(bad.patients[0].name, "");
}

TEST(ScanDicom, CtStrippedOfPreambleAndMetaHeaderGivesTheSameRecords) {
  TempDir dir;
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(data_dir("dicom/CT_small.dcm").c_str()).good());
  const std::string stripped = dir.file("ct_dataset_only");
  ASSERT_TRUE(file.saveFile(stripped.c_str(), EXS_LittleEndianImplicit, EET_UndefinedLength, EGL_recalcGL, EPD_noChange,
                            0, 0, EWM_dataset)
                  .good());
  std::ifstream in(stripped, std::ios::binary);
  char head[4] = {};
  in.read(head, 4);
  ASSERT_EQ(head[0], 0x08) << "the file should start with a group 0008 tag";
  const DicomScan s = scan({stripped});
  ASSERT_EQ(s.files_read, 1);
  EXPECT_EQ(s.patients[0].patient_id, "1CT1");
  EXPECT_EQ(s.series[0].series_uid, "1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322");
}

TEST(ScanDicom, NonDicomFilesAreSkippedAndCounted) {
  const DicomScan s = scan({data_dir("dicom/README.md"), data_dir("dicom/facts.json"), data_dir("dicom/CT_small.dcm")});
  EXPECT_EQ(s.non_dicom_skipped, 2);
  EXPECT_EQ(s.files_read, 1);
  EXPECT_TRUE(s.unreadable.empty());
}

TEST(ScanDicom, CorruptDicomIsReportedWithItsNameAndTheScanGoesOn) {
  TempDir dir;
  std::ifstream in(data_dir("dicom/CT_small.dcm"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Keep the preamble and meta header, then garble the dataset: a huge odd element length.
  const std::string corrupt = dir.file("corrupt.dcm");
  std::string head = bytes.substr(0, 400);
  for (size_t i = 340; i < 400; ++i) head[i] = '\xff';
  std::ofstream(corrupt, std::ios::binary) << head;
  fs::copy_file(data_dir("dicom/MR_small.dcm"), dir.file("mr.dcm"));
  const DicomScan s = scan({dir.path().string()});
  EXPECT_EQ(s.files_read, 1);
  ASSERT_EQ(s.unreadable.size(), 1u);
  EXPECT_EQ(s.unreadable[0].path, corrupt);
  EXPECT_EQ(s.unreadable[0].status.code(), StatusCode::kDataLoss);
  EXPECT_NE(s.unreadable[0].status.message().find("corrupt.dcm"), std::string::npos)
      << s.unreadable[0].status.message();
}

TEST(ScanDicom, TruncatedDicomIsReportedNotCrashed) {
  TempDir dir;
  std::ifstream in(data_dir("dicom/rtstruct.dcm"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string truncated = dir.file("truncated.dcm");
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, 1000);
  const DicomScan s = scan({truncated});
  EXPECT_EQ(s.files_read, 0);
  ASSERT_EQ(s.unreadable.size(), 1u);
  EXPECT_NE(s.unreadable[0].status.message().find("truncated.dcm"), std::string::npos);
}

TEST(ScanDicom, MissingPathIsNotFound) {
  auto r = scan_dicom({data_dir("dicom/no_such_file.dcm")});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
  EXPECT_NE(r.status().message().find("no_such_file.dcm"), std::string::npos);
}

// Every DICOMDIR variant indexes the same 2 patients, 6 studies, 13 series and 31 images.
class DicomdirVariant : public ::testing::TestWithParam<std::string> {};

TEST_P(DicomdirVariant, IndexesTwoPatientsSixStudiesThirteenSeries) {
  const DicomScan s = scan({data_dir("dicom/dicomdirtests/" + GetParam())});
  EXPECT_TRUE(s.unreadable.empty()) << s.unreadable[0].status.to_string();
  EXPECT_EQ(s.dicomdirs_read, 1);
  EXPECT_EQ(s.files_read, 31);
  ASSERT_EQ(s.patients.size(), 2u);
  EXPECT_EQ(s.patients[0].patient_id, "77654033");
  EXPECT_EQ(s.patients[1].patient_id, "98890234");
  EXPECT_EQ(s.studies.size(), 6u);
  EXPECT_EQ(s.series.size(), 13u);
}

INSTANTIATE_TEST_SUITE_P(ScanDicom, DicomdirVariant,
                         ::testing::Values("DICOMDIR", "DICOMDIR-bigEnd", "DICOMDIR-implicit", "DICOMDIR-nooffset",
                                           "DICOMDIR-reordered", "DICOMDIR-nopatient"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

TEST(ScanDicom, DicomdirStudiesHaveTheirDescriptionsAndAges) {
  const DicomScan s = scan({data_dir("dicom/dicomdirtests/DICOMDIR")});
  int ct_head = 0, spine = 0;
  for (const auto& st : s.studies) {
    if (st.description == "CT, HEAD/BRAIN WO CONTRAST") ++ct_head;
    if (st.description == "XR C Spine Comp Min 4 Views") {
      ++spine;
      EXPECT_EQ(st.patient_id, "77654033");
      ASSERT_TRUE(st.age_years.has_value());  // Patient's Age 047Y
      EXPECT_EQ(*st.age_years, 47.0);
    }
  }
  EXPECT_EQ(ct_head, 1);
  EXPECT_EQ(spine, 1);
  const DicomPatient* peter = s.find_patient("98890234");
  ASSERT_NE(peter, nullptr);
  EXPECT_EQ(peter->sex, "M");
}

TEST(ScanDicom, EmptyDicomdirHasNoRecords) {
  const DicomScan s = scan({data_dir("dicom/dicomdirtests/DICOMDIR-empty.dcm")});
  EXPECT_EQ(s.dicomdirs_read, 1);
  EXPECT_EQ(s.files_read, 0);
  EXPECT_TRUE(s.unreadable.empty());
}

TEST(ScanDicom, DicomdirWithoutItsDescriptorFileIsRead) {
  const DicomScan s = scan({data_dir("dicom/dicomdirtests/TINY_ALPHA/DICOMDIR")});
  EXPECT_TRUE(s.unreadable.empty());
  EXPECT_EQ(s.files_read, 50);
  ASSERT_EQ(s.patients.size(), 1u);
  EXPECT_EQ(s.patients[0].patient_id, "12345678");
  ASSERT_EQ(s.studies.size(), 1u);
  EXPECT_EQ(s.studies[0].description, "Testing File-set");
  ASSERT_EQ(s.series.size(), 1u);
  EXPECT_EQ(s.series[0].modality, "CT");
}

TEST(ScanDicom, FolderWithDicomdirsReadsEachFileOnce) {
  // Seven DICOMDIRs and a recursive walk all reach the same 31 + 50 files.
  const DicomScan s = scan({data_dir("dicom/dicomdirtests")});
  EXPECT_EQ(s.files_read, 81);
  EXPECT_EQ(s.dicomdirs_read, 8);
  EXPECT_EQ(s.patients.size(), 3u);
  EXPECT_EQ(s.non_dicom_skipped, 1);  // README.txt
  EXPECT_TRUE(s.unreadable.empty());
}

TEST(ScanDicom, StsPetStudyHasPatientAgeAndSex) {
  const DicomScan s = scan({data_dir("sts/STS_002/dicom/PET")});
  ASSERT_EQ(s.patients.size(), 1u);
  EXPECT_EQ(s.patients[0].patient_id, "STS_002");
  EXPECT_EQ(s.patients[0].sex, "M");
  ASSERT_EQ(s.studies.size(), 1u);
  EXPECT_EQ(s.studies[0].study_date, "20060128");
  ASSERT_TRUE(s.studies[0].age_years.has_value());
  EXPECT_EQ(*s.studies[0].age_years, 61.0);  // Patient's Age 061Y
  ASSERT_EQ(s.series.size(), 2u);            // the PET images and their RTSTRUCT
  EXPECT_EQ(s.series[0].study_uid, s.series[1].study_uid);
  EXPECT_EQ(s.files_read, 49);
}

}  // namespace
}  // namespace soiq::dicom
