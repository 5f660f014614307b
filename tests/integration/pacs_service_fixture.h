#pragma once
// A real soiqd started with --pacs against its own real PACS on loopback: DCMTK's dcmqrscp loaded
// with DCMTK's storescu (tests/support/dcmqrscp_process.h) with STS_002 and CT_small.dcm. Each test
// has its own PACS and its own soiqd, so none sees another's pushes.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tests/integration/service_fixture.h"
#include "tests/support/dcmqrscp_process.h"
#include "tests/support/test_data.h"

namespace soiq::testing {

using dicom::testing::DcmqrscpProcess;

inline constexpr const char* kStsStudyUid = "1.3.6.1.4.1.14519.5.2.1.5168.1900.190311276211389538203367070477";
inline constexpr int kStsFiles = 98;  // 48 CT + 48 PET slices + 2 RT Structure Sets

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class PacsServiceTest : public ServiceTest {
 protected:
  void SetUp() override {
    const std::string error = pacs_.start();
    if (error.rfind("not installed", 0) == 0) GTEST_SKIP() << error;
    ASSERT_EQ(error, "");
    ASSERT_EQ(pacs_.load({test_data("sts/STS_002/dicom"), test_data("dicom/CT_small.dcm")}), "");
    start_with_pacs(pacs_address());
  }

  std::string pacs_address() const {
    return std::string(DcmqrscpProcess::kAeTitle) + "@127.0.0.1:" + std::to_string(pacs_.port());
  }

  void start_with_pacs(const std::string& address, const std::vector<std::string>& more = {}) {
    std::vector<std::string> args = {"--pacs-timeout", "5"};
    if (!address.empty()) args.insert(args.end(), {"--pacs", address});
    args.insert(args.end(), more.begin(), more.end());
    start(args);
    client_ = std::make_unique<client::Client>(connect());
  }

  // The structure imported on the CT series of a pull or import.
  static const v1::ImportedStructure* on_modality(const v1::ImportDicomResponse& r, const std::string& modality) {
    for (const v1::Series& s : r.series()) {
      if (s.modality() != modality) continue;
      for (const v1::ImportedStructure& i : r.structures())
        if (i.referenced_series_uid() == s.series_uid()) return &i;
    }
    return nullptr;
  }

  Result<v1::ImportDicomResponse> pull_sts(const std::function<bool(const v1::PacsPullProgress&)>& progress = {}) {
    v1::PacsPullRequest r;
    r.add_study_uids(kStsStudyUid);
    return client_->pacs_pull(r, progress);
  }

  int64_t stored_structures() {
    Result<v1::ServerInfo> info = client_->server_info();
    EXPECT_TRUE(info.ok());
    return info.ok() ? info->structures() + info->series() : -1;
  }

  DcmqrscpProcess pacs_;
};

}  // namespace soiq::testing
