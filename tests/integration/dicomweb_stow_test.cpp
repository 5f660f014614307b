// STOW-RS through a real soiqd --http: a study sent as multipart/related is stored as `soiq import`
// stores the same files (a later query finds its structure with the same values), each instance's
// outcome is in the PS3.18 response, and bad requests get their HTTP status.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/integration/dicomweb_fixture.h"
#include "tests/integration/sts_query.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

// The DICOM files under `folder` (sorted), as the parts of a request.
std::vector<std::string> dicom_files(const std::string& folder) {
  std::vector<std::string> paths;
  for (const auto& e : std::filesystem::recursive_directory_iterator(test_data(folder)))
    if (e.path().extension() == ".dcm") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  std::vector<std::string> out;
  for (const std::string& p : paths) out.push_back(file_bytes(p));
  return out;
}

class DicomwebStowTest : public DicomwebTest {
 protected:
  httplib::Result post(const std::string& path, const std::vector<std::string>& parts,
                       const std::string& type = "application/dicom") {
    const std::string boundary = "stow-test-boundary-7d1c";
    std::string body;
    for (const std::string& p : parts) body += "--" + boundary + "\r\nContent-Type: " + type + "\r\n\r\n" + p + "\r\n";
    body += "--" + boundary + "--\r\n";
    return http_->Post(path.c_str(), body, ("multipart/related; type=\"" + type + "\"; boundary=" + boundary).c_str());
  }

  static size_t count(const json& response, const char* sequence) {
    return response.contains(sequence) ? response[sequence]["Value"].size() : 0;
  }
};

TEST_F(DicomwebStowTest, AStudySentIsStoredAsAnImportStoresItAndQueriesFindIt) {
  std::vector<std::string> parts = dicom_files("sts/STS_002/dicom/CT");
  for (const std::string& p : dicom_files("sts/STS_002/dicom/PET")) parts.push_back(p);
  httplib::Result r = post("/dicom-web/studies", parts);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/dicom+json");
  const json response = json::parse(r->body);
  EXPECT_EQ(count(response, "00081199"), parts.size());
  EXPECT_EQ(count(response, "00081198"), 0u);
  const json first = response["00081199"]["Value"][0];
  EXPECT_FALSE(value(first, "00081155").empty());
  EXPECT_FALSE(value(first, "00081150").empty());

  // The same query on a second soiqd that imported the same files with `soiq import`'s call.
  Result<QueryResult> via_stow = run_query(*client_, gtv_mean_pet_query());
  ASSERT_TRUE(via_stow.ok()) << via_stow.status().to_string();
  ASSERT_EQ(via_stow->rows.size(), 2u);
  TempDir other;
  SoiqdProcess imported(other.file("soiq.db"));
  client::ClientOptions options;
  options.address = imported.address();
  options.retry.attempts = 1;
  Result<client::Client> c = client::Client::connect(options);
  ASSERT_TRUE(c.ok());
  ASSERT_TRUE(c->import_dicom({test_data("sts/STS_002/dicom")}).ok());
  Result<QueryResult> via_import = run_query(*c, gtv_mean_pet_query());
  ASSERT_TRUE(via_import.ok());
  // By structure name: the ids follow the order files arrive in.
  const auto by_name = [](const QueryResult& q) {
    std::map<std::string, double> out;
    for (const v1::QueryRow& row : q.rows) out[row.structure().name()] = row.values(0).value(0);
    return out;
  };
  EXPECT_EQ(by_name(*via_stow), by_name(*via_import));
  EXPECT_EQ(by_name(*via_stow).size(), 2u);
}

TEST_F(DicomwebStowTest, EachInstanceHasItsOutcomeAndAReason) {
  std::vector<std::string> parts = dicom_files("sts/STS_002/dicom/CT/image");
  parts.push_back(file_bytes(test_data("dicom/rtstruct.dcm")));  // its image series is not sent
  parts.push_back("not DICOM at all");
  httplib::Result r = post("/dicom-web/studies", parts);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 202) << r->body;  // some stored, some not
  const json response = json::parse(r->body);
  EXPECT_EQ(count(response, "00081199"), parts.size() - 2);
  ASSERT_EQ(count(response, "00081198"), 2u);
  const json failed = response["00081198"]["Value"];
  EXPECT_EQ(value(failed[0], "00081197"), std::to_string(0x0110));  // processing failure
  EXPECT_EQ(value(failed[1], "00081197"), std::to_string(0xC000));  // cannot understand
  EXPECT_NE(r->get_header_value("Warning").find("references image series"), std::string::npos)
      << r->get_header_value("Warning");
}

TEST_F(DicomwebStowTest, AnInstanceOfAnotherStudyThanTheUrlsIsRefused) {
  httplib::Result r = post("/dicom-web/studies/1.2.3.4", dicom_files("sts/STS_002/dicom/CT/image"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409) << r->body;  // nothing stored
  const json response = json::parse(r->body);
  EXPECT_EQ(value(response["00081198"]["Value"][0], "00081197"), std::to_string(0xA900));
  EXPECT_EQ(value(response, "00081190"),
            "http://127.0.0.1:" + std::to_string(server_->http_port()) + "/dicom-web/studies/1.2.3.4");
  EXPECT_TRUE(get("/dicom-web/studies").empty());
}

TEST_F(DicomwebStowTest, BadRequestsGetTheirStatus) {
  const std::string ct = file_bytes(test_data("dicom/CT_small.dcm"));
  httplib::Result plain = http_->Post("/dicom-web/studies", ct, "application/dicom");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->status, 415);
  httplib::Result xml = post("/dicom-web/studies", {ct}, "application/dicom+xml");
  ASSERT_TRUE(xml);
  EXPECT_EQ(xml->status, 415);
  httplib::Result no_boundary = http_->Post("/dicom-web/studies", ct, "multipart/related; type=\"application/dicom\"");
  ASSERT_TRUE(no_boundary);
  EXPECT_EQ(no_boundary->status, 400);
  EXPECT_NE(no_boundary->body.find("boundary"), std::string::npos);
  httplib::Result empty = post("/dicom-web/studies", {});
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->status, 400);

  start_http({"--max-upload-bytes", "100000"});
  httplib::Result big = post("/dicom-web/studies", dicom_files("sts/STS_002/dicom/CT/image"));
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  EXPECT_NE(big->body.find("max-upload-bytes"), std::string::npos) << big->body;
  EXPECT_TRUE(get("/dicom-web/studies").empty());
}

}  // namespace
}  // namespace soiq::testing

namespace soiq::testing {
namespace {

// A study sent again with one slice's pixels changed: the stored series keeps its content, each
// part of that series fails as a duplicate SOP instance (0111), and the Warning says what differs.
TEST_F(DicomwebStowTest, InstancesStoredWithOtherContentAreDuplicatesAndNothingChanges) {
  std::vector<std::string> slices = dicom_files("sts/STS_002/dicom/CT/image");
  httplib::Result first = post("/dicom-web/studies", slices);
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 200) << first->body;
  httplib::Result same = post("/dicom-web/studies", slices);
  ASSERT_TRUE(same);
  EXPECT_EQ(same->status, 200) << same->body;  // the same content: stored already, a no-op
  slices[10].back() = char(slices[10].back() ^ 0x01);
  httplib::Result other = post("/dicom-web/studies", slices);
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 409) << other->body;
  const json response = json::parse(other->body);
  ASSERT_EQ(count(response, "00081198"), slices.size());
  for (const json& failed : response["00081198"]["Value"]) EXPECT_EQ(failed["00081197"]["Value"][0], 0x0111);
  EXPECT_NE(other->get_header_value("Warning").find("voxels differ"), std::string::npos)
      << other->get_header_value("Warning");
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->series(), 1);
}

}  // namespace
}  // namespace soiq::testing
