#pragma once
// A real soiqd with DICOMweb (--http on a free port) and an HTTP client to it, for the DICOMweb
// integration tests; DICOM JSON helpers.

#include <gtest/gtest.h>
#include <httplib.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/integration/service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {

using nlohmann::json;

inline constexpr char kStudyUid[] = "0020000D";
inline constexpr char kSeriesUid[] = "0020000E";
inline constexpr char kSopUid[] = "00080018";

// The first value of a DICOM JSON attribute as text ("" when absent or without a value).
inline std::string value(const json& item, const char* tag) {
  if (!item.contains(tag) || !item[tag].contains("Value")) return "";
  const json& v = item[tag]["Value"][0];
  if (v.is_object()) return v.value("Alphabetic", "");
  return v.is_string() ? v.get<std::string>() : v.dump();
}

class DicomwebTest : public ServiceTest {
 protected:
  void SetUp() override { start_http({"--keep-patient-names", "on"}); }

  void start_http(std::vector<std::string> args) {
    args.insert(args.begin(), {"--http", "127.0.0.1:0"});
    start(args);
    ASSERT_GT(server_->http_port(), 0) << server_->log();
    client_ = std::make_unique<client::Client>(connect());
    http_ = std::make_unique<httplib::Client>("127.0.0.1", server_->http_port());
  }

  void import(const std::string& folder) {
    Result<v1::ImportDicomResponse> r = client_->import_dicom({test_data(folder)});
    ASSERT_TRUE(r.ok()) << r.status().to_string();
  }

  // GET `path` and the JSON array it answers; fails the test on another status.
  json get(const std::string& path, int expected_status = 200) {
    httplib::Result r = http_->Get(path.c_str());
    if (!r) {
      ADD_FAILURE() << "GET " << path << ": no answer";
      return json();
    }
    EXPECT_EQ(r->status, expected_status) << path << ": " << r->body;
    if (expected_status == 200) {
      EXPECT_EQ(r->get_header_value("Content-Type"), "application/dicom+json");
    }
    return json::parse(r->body, nullptr, false);
  }

  std::vector<std::string> values(const json& items, const char* tag) {
    std::vector<std::string> out;
    for (const json& i : items) out.push_back(value(i, tag));
    return out;
  }

  std::unique_ptr<httplib::Client> http_;
};

}  // namespace soiq::testing
