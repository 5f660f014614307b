// A PACS pull's transfer on its own, against a real PACS (DCMTK's dcmqrscp on a free loopback
// port): the files of a study land in the folder with progress, and every refusal comes before or
// instead of an import.
#include "server/app/pacs_pull_studies.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/dcmqrscp_process.h"

namespace soiq::server {
namespace {

using dicom::testing::DcmqrscpProcess;
using soiq::testing::TempDir;

constexpr const char* kCtSmallStudyUid = "1.3.6.1.4.1.5962.1.2.1.20040119072730.12322";

class PacsPullStudies : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pacs_ = new DcmqrscpProcess();
    start_error_ = pacs_->start();
    if (start_error_.empty()) start_error_ = pacs_->load({std::string(SOIQ_TEST_DATA_DIR) + "/dicom/CT_small.dcm"});
  }
  static void TearDownTestSuite() {
    delete pacs_;
    pacs_ = nullptr;
  }
  void SetUp() override { ASSERT_EQ(start_error_, "") << "the test PACS did not start"; }

  Result<PulledFiles> pull(const PullRequest& r, int64_t max_bytes = int64_t(1) << 30,
                           std::function<bool(const PullProgress&)> progress = {}) {
    return pacs_pull_studies(pacs_->peer(), r, dir_.path().string(), max_bytes, progress);
  }

  static DcmqrscpProcess* pacs_;
  static std::string start_error_;
  TempDir dir_;
};
DcmqrscpProcess* PacsPullStudies::pacs_ = nullptr;
std::string PacsPullStudies::start_error_;

TEST_F(PacsPullStudies, AStudyArrivesAsItsFilesWithProgress) {
  std::vector<PullProgress> seen;
  Result<PulledFiles> r = pull({{kCtSmallStudyUid}, ""}, int64_t(1) << 30, [&](const PullProgress& p) {
    seen.push_back(p);
    return true;
  });
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->studies, 1);
  ASSERT_EQ(r->paths.size(), 1u);
  EXPECT_GT(r->bytes, 0);
  EXPECT_TRUE(std::filesystem::exists(dir_.path() / r->paths[0])) << r->paths[0];
  EXPECT_EQ(r->paths[0].rfind("1/", 0), 0u) << "study 1 goes to DIR/1/: " << r->paths[0];
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back().study, 1);
  EXPECT_EQ(seen.back().studies, 1);
  EXPECT_EQ(seen.back().received, 1);
}

TEST_F(PacsPullStudies, NeitherOrBothOfStudiesAndPatientIsInvalidArgument) {
  EXPECT_EQ(pull({{}, ""}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(pull({{kCtSmallStudyUid}, "P"}).status().code(), StatusCode::kInvalidArgument);
}

TEST_F(PacsPullStudies, AStudyNamedTwiceOrAWildcardPatientIsInvalidArgument) {
  EXPECT_EQ(pull({{kCtSmallStudyUid, kCtSmallStudyUid}, ""}).status().code(), StatusCode::kInvalidArgument);
  Result<PulledFiles> wildcard = pull({{}, "STS_*"});
  EXPECT_EQ(wildcard.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(wildcard.status().message().find("wildcard"), std::string::npos) << wildcard.status().message();
}

TEST_F(PacsPullStudies, MoreBytesThanTheLimitIsResourceExhaustedNamingIt) {
  Result<PulledFiles> r = pull({{kCtSmallStudyUid}, ""}, 100);
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(r.status().message().find("--max-upload-bytes"), std::string::npos) << r.status().message();
}

TEST_F(PacsPullStudies, ProgressReturningFalseCancelsThePull) {
  Result<PulledFiles> r = pull({{kCtSmallStudyUid}, ""}, int64_t(1) << 30, [](const PullProgress&) { return false; });
  EXPECT_EQ(r.status().code(), StatusCode::kCancelled);
}

TEST_F(PacsPullStudies, APatientWithoutStudiesOnThePacsIsNotFound) {
  Result<PulledFiles> r = pull({{}, "NOBODY_HERE"});
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
  EXPECT_NE(r.status().message().find("NOBODY_HERE"), std::string::npos) << r.status().message();
}

}  // namespace
}  // namespace soiq::server
