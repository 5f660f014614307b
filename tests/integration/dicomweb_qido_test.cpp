// QIDO-RS through a real soiqd --http, over real HTTP (cpp-httplib's client): STS_002 and the
// pydicom CT and MR samples imported from DICOM, listed as studies, series and instances; paging, includefield, name
// matching, the SEG and RT Structure Set series of each structure, and the errors a client gets.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "dicom/scan_dicom.h"
#include "tests/integration/dicomweb_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

using nlohmann::json;

TEST_F(DicomwebTest, StudiesSeriesAndInstancesOfImportedPatients) {
  import("sts/STS_002/dicom");
  import("dicom/CT_small.dcm");
  const json studies = get("/dicom-web/studies");
  ASSERT_EQ(studies.size(), 2u);
  const json& sts2 = studies[0];
  EXPECT_EQ(value(sts2, "00100020"), "STS_002");
  EXPECT_EQ(value(sts2, "00100010"), "STS_002");  // the files' Patient's Name, kept
  EXPECT_EQ(sts2["00080061"]["Value"], json({"CT", "PT", "RTSTRUCT", "SEG"}));
  EXPECT_EQ(value(sts2, "00201206"), "6");  // CT, PT and a SEG and an RT Structure Set per structure
  EXPECT_EQ(value(sts2, "00080005"), "ISO_IR 192");
  const std::string study = value(sts2, kStudyUid);
  EXPECT_EQ(value(sts2, "00081190"),
            "http://127.0.0.1:" + std::to_string(server_->http_port()) + "/dicom-web/studies/" + study);

  // Series: the images, then a SEG and an RT Structure Set per structure, each findable by its UID.
  const json series = get("/dicom-web/studies/" + study + "/series");
  ASSERT_EQ(series.size(), 6u);
  EXPECT_EQ(values(series, "00080060"), (std::vector<std::string>{"CT", "PT", "SEG", "RTSTRUCT", "SEG", "RTSTRUCT"}));
  EXPECT_EQ(value(series[3], "0008103E"), value(series[2], "0008103E"));  // the structure's name
  EXPECT_EQ(value(series[3], "00200011"), "901");
  for (const json& s : series) {
    const json again = get("/dicom-web/series?SeriesInstanceUID=" + value(s, kSeriesUid));
    ASSERT_EQ(again.size(), 1u);
    EXPECT_EQ(value(again[0], kStudyUid), study);
  }

  // The CT's instances are the SOP instances of the files imported, in slice order.
  const std::string ct = value(series[0], kSeriesUid);
  const json instances = get("/dicom-web/studies/" + study + "/series/" + ct + "/instances");
  Result<dicom::DicomScan> scan = dicom::scan_dicom({test_data("sts/STS_002/dicom/CT/image")});
  ASSERT_TRUE(scan.ok());
  std::set<std::string> files;
  for (const dicom::DicomSeries& s : scan->series)
    for (const dicom::DicomInstance& i : s.instances) files.insert(i.sop_instance_uid);
  const std::vector<std::string> listed = values(instances, kSopUid);
  EXPECT_EQ(std::set<std::string>(listed.begin(), listed.end()), files);
  EXPECT_EQ(listed.size(), files.size());
  EXPECT_EQ(value(instances[0], "00200013"), "1");
  EXPECT_EQ(value(instances[0], "00080016"), "1.2.840.10008.5.1.4.1.1.2");

  // A SEG series has one instance, of the Segmentation SOP class.
  const json seg = get("/dicom-web/studies/" + study + "/series/" + value(series[2], kSeriesUid) + "/instances");
  ASSERT_EQ(seg.size(), 1u);
  EXPECT_EQ(value(seg[0], "00080016"), "1.2.840.10008.5.1.4.1.1.66.4");
  EXPECT_EQ(get("/dicom-web/instances?SOPInstanceUID=" + value(seg[0], kSopUid)).size(), 1u);

  // An RT Structure Set series likewise, of the RT Structure Set Storage SOP class.
  const json rt = get("/dicom-web/studies/" + study + "/series/" + value(series[3], kSeriesUid) + "/instances");
  ASSERT_EQ(rt.size(), 1u);
  EXPECT_EQ(value(rt[0], "00080016"), "1.2.840.10008.5.1.4.1.1.481.3");
  EXPECT_EQ(value(rt[0], "00080060"), "RTSTRUCT");
  EXPECT_NE(value(rt[0], kSopUid), value(seg[0], kSopUid));
  EXPECT_EQ(get("/dicom-web/instances?SOPInstanceUID=" + value(rt[0], kSopUid)).size(), 1u);

  // Modality filters pick either object; counts and paging include both.
  EXPECT_EQ(get("/dicom-web/studies/" + study + "/series?Modality=RTSTRUCT").size(), 2u);
  EXPECT_EQ(get("/dicom-web/studies/" + study + "/series?Modality=SEG").size(), 2u);
  EXPECT_EQ(values(get("/dicom-web/studies/" + study + "/series?offset=3&limit=2"), kSeriesUid),
            (std::vector<std::string>{value(series[3], kSeriesUid), value(series[4], kSeriesUid)}));
  EXPECT_EQ(get("/dicom-web/studies/" + study + "/instances?Modality=RTSTRUCT").size(), 2u);
  EXPECT_EQ(get("/dicom-web/studies?ModalitiesInStudy=RTSTRUCT").size(), 1u);
}

TEST_F(DicomwebTest, PagesCoverEveryStudyOnceInOneOrder) {
  for (const char* p : {"sts/STS_002/dicom/CT", "dicom/CT_small.dcm", "dicom/MR_small.dcm"}) import(p);
  const std::vector<std::string> all = values(get("/dicom-web/studies"), kStudyUid);
  ASSERT_EQ(all.size(), 3u);
  std::vector<std::string> paged;
  for (int offset = 0; offset < 4; offset += 2) {
    const json page = get("/dicom-web/studies?limit=2&offset=" + std::to_string(offset));
    for (const std::string& uid : values(page, kStudyUid)) paged.push_back(uid);
  }
  EXPECT_EQ(paged, all);
  EXPECT_TRUE(get("/dicom-web/studies?offset=3").empty());
  // A limit past the server's is clamped, and said so.
  httplib::Result r = http_->Get("/dicom-web/studies?limit=5000");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->get_header_value("Warning").find("299"), std::string::npos);
}

TEST_F(DicomwebTest, IncludefieldAddsAttributesAndMatchingKeysFilter) {
  import("sts/STS_002/dicom/CT");
  import("dicom/CT_small.dcm");  // patient 1CT1, CompressedSamples^CT1
  const json plain = get("/dicom-web/studies?PatientID=STS_002");
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_FALSE(plain[0].contains("00101010"));  // PatientAge: only when asked
  const json aged = get("/dicom-web/studies?PatientID=STS_002&includefield=PatientAge,00081030");
  EXPECT_TRUE(aged[0].contains("00101010"));
  EXPECT_TRUE(aged[0].contains("00081030"));
  EXPECT_TRUE(get("/dicom-web/studies?PatientID=STS_002&includefield=all")[0].contains("00101010"));

  EXPECT_EQ(values(get("/dicom-web/studies?PatientID=%3FCT%3F"), "00100020"), std::vector<std::string>{"1CT1"});
  EXPECT_EQ(get("/dicom-web/studies?PatientID=*").size(), 2u);
  EXPECT_EQ(get("/dicom-web/studies?PatientName=sts_002").size(), 1u);  // names ignore case
  EXPECT_EQ(get("/dicom-web/studies?PatientName=*ct1").size(), 1u);
  EXPECT_EQ(get("/dicom-web/studies?PatientName=ct1").size(), 0u);  // the whole name, without fuzzy matching
  EXPECT_EQ(values(get("/dicom-web/studies?PatientName=ct&fuzzymatching=true"), "00100020"),
            std::vector<std::string>{"1CT1"});
  EXPECT_EQ(get("/dicom-web/studies?ModalitiesInStudy=SEG").size(), 1u);
  EXPECT_EQ(get("/dicom-web/studies?ModalitiesInStudy=CT").size(), 2u);
  EXPECT_EQ(get("/dicom-web/studies?ModalitiesInStudy=PT").size(), 0u);
  const std::string date = value(plain[0], "00080020");
  EXPECT_EQ(values(get("/dicom-web/studies?StudyDate=" + date + "-" + date), "00100020"),
            std::vector<std::string>{"STS_002"});
  EXPECT_EQ(get("/dicom-web/series?Modality=CT").size(), 2u);
  EXPECT_EQ(get("/dicom-web/series?Modality=CT&PatientID=1CT1").size(), 1u);
}

TEST_F(DicomwebTest, ErrorsAreHttpStatusesWithAJsonBodyNamingTheProblem) {
  import("sts/STS_002/dicom/CT");
  const std::vector<std::pair<std::string, int>> cases = {
      {"/dicom-web/studies?Frobnicate=1", 400},
      {"/dicom-web/studies?StudyDate=2020", 400},
      {"/dicom-web/studies?limit=0", 400},
      {"/dicom-web/studies?offset=-1", 400},
      {"/dicom-web/studies?fuzzymatching=yes", 400},
      {"/dicom-web/studies?PatientID=a&PatientID=b", 400},
      {"/dicom-web/studies?StudyDescription=x", 400},
      {"/dicom-web/studies/1.2.3/series", 404},
      {"/dicom-web/nothing", 404},
  };
  for (const auto& [path, status] : cases) {
    const json body = get(path, status);
    ASSERT_TRUE(body.is_object()) << path;
    EXPECT_EQ(body["error"]["status"], status) << path;
    EXPECT_FALSE(body["error"]["message"].get<std::string>().empty()) << path;
  }
  httplib::Headers xml = {{"Accept", "application/dicom+xml"}};
  httplib::Result r = http_->Get("/dicom-web/studies", xml);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 406);
}

TEST_F(DicomwebTest, NamesAreDroppedUnlessSoiqdKeepsThem) {
  start_http({});
  import("sts/STS_002/dicom/CT");
  const json studies = get("/dicom-web/studies");
  ASSERT_EQ(studies.size(), 1u);
  EXPECT_EQ(value(studies[0], "00100010"), "");
  EXPECT_TRUE(studies[0].contains("00100010"));  // present, empty (Type 2)
  const json refused = get("/dicom-web/studies?PatientName=STS*", 400);
  EXPECT_NE(refused["error"]["message"].get<std::string>().find("--keep-patient-names"), std::string::npos);
}

TEST_F(DicomwebTest, HttpsWithTheCertificateOfGrpc) {
  const std::string key = dir_.file("key.pem"), cert = dir_.file("cert.pem");
  const std::string cmd = "openssl req -x509 -newkey rsa:2048 -nodes -keyout " + key + " -out " + cert +
                          " -days 1 -subj /CN=localhost -addext subjectAltName=DNS:localhost 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "openssl could not make a test certificate";
  start_http({"--tls-cert", cert, "--tls-key", key});
  httplib::SSLClient https("localhost", server_->http_port());
  https.set_ca_cert_path(cert.c_str());
  https.enable_server_certificate_verification(true);
  httplib::Result r = https.Get("/dicom-web/studies");
  ASSERT_TRUE(r) << httplib::to_string(r.error()) << "\n" << server_->log();
  EXPECT_EQ(r->status, 200);
  // Plain HTTP to the TLS port gets no answer.
  httplib::Result plain = http_->Get("/dicom-web/studies");
  EXPECT_FALSE(plain && plain->status == 200);
}

TEST_F(DicomwebTest, TheTokenOfGrpcGuardsDicomwebToo) {
  const std::string token_file = dir_.file("token");
  { std::ofstream(token_file) << "0123456789abcdef0123\n"; }
  start_http({"--token-file", token_file});
  httplib::Result none = http_->Get("/dicom-web/studies");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 401);
  EXPECT_EQ(none->get_header_value("WWW-Authenticate"), "Bearer");
  httplib::Result wrong = http_->Get("/dicom-web/studies", {{"Authorization", "Bearer 0123456789abcdef0124"}});
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 401);
  httplib::Result right = http_->Get("/dicom-web/studies", {{"Authorization", "Bearer 0123456789abcdef0123"}});
  ASSERT_TRUE(right);
  EXPECT_EQ(right->status, 200);
  EXPECT_EQ(right->body, "[]");
}

}  // namespace
}  // namespace soiq::testing
