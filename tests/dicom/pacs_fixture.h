#pragma once
// The PACS the tests of dicom/pacs_*.h talk to: DCMTK's dcmqrscp on loopback, loaded with DCMTK's
// storescu (tests/support/dcmqrscp_process.h) once per test suite with STS_002 (CT, PET, two RT
// Structure Sets), CT_small.dcm and rtstruct.dcm: 3 patients, 3 studies, 100 instances. Expected
// values are read from the files themselves (tests/data/dicom/facts.json, dcmdump of
// tests/data/sts/STS_002).

#include <gtest/gtest.h>

#include <string>

#include "dicom/pacs_client.h"
#include "dicom_test_support.h"
#include "tests/support/dcmqrscp_process.h"

namespace soiq::dicom {

inline constexpr const char* kStsStudyUid = "1.3.6.1.4.1.14519.5.2.1.5168.1900.190311276211389538203367070477";
inline constexpr const char* kCtSmallStudyUid = "1.3.6.1.4.1.5962.1.2.1.20040119072730.12322";
inline constexpr const char* kMrSmallStudyUid = "1.3.6.1.4.1.5962.1.2.4.20040826185059.5457";
inline constexpr int kStsFiles = 98;  // 48 CT + 48 PET slices + 2 RT Structure Sets

// Derive a suite from it (class PacsFind : public LoadedPacs {}): each suite loads its own PACS.
class LoadedPacs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pacs_ = new testing::DcmqrscpProcess();
    setup_error_ = pacs_->start();
    if (setup_error_.empty())
      setup_error_ = pacs_->load({testing::data_dir("sts/STS_002/dicom"), testing::data_dir("dicom/CT_small.dcm"),
                                  testing::data_dir("dicom/rtstruct.dcm")});
  }
  static void TearDownTestSuite() {
    delete pacs_;
    pacs_ = nullptr;
  }
  void SetUp() override {
    if (setup_error_.rfind("not installed", 0) == 0) GTEST_SKIP() << setup_error_;
    ASSERT_EQ(setup_error_, "");
  }
  static PacsPeer peer() { return pacs_->peer(); }

  inline static testing::DcmqrscpProcess* pacs_ = nullptr;
  inline static std::string setup_error_;
};

}  // namespace soiq::dicom
