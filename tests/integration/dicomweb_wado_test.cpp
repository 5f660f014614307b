// WADO-RS through a real soiqd --http: a structure's SEG retrieved as DICOM, its metadata and its
// Pixel Data; the voxels are those the import converted and those ExportSeg writes; its RT
// Structure Set retrieved, with the contours ExportRtStruct writes; what soiq cannot send is
// refused saying why (tests/dicomweb_instances judges the image instances it keeps).
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "dicom/dicom_json_metadata.h"
#include "tests/integration/dicomweb_fixture.h"
#include "tests/support/address_sanitizer.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

// The parts of a multipart/related answer (a small reader of its own: the server's is under test).
std::vector<std::string> parts_of(const httplib::Result& r) {
  const std::string ct = r->get_header_value("Content-Type");
  const std::string boundary = "--" + ct.substr(ct.find("boundary=") + 9);
  std::vector<std::string> parts;
  size_t at = r->body.find(boundary);
  while (at != std::string::npos && r->body.compare(at + boundary.size(), 2, "--") != 0) {
    const size_t start = r->body.find("\r\n\r\n", at) + 4;
    const size_t end = r->body.find("\r\n" + boundary, start);
    parts.push_back(r->body.substr(start, end - start));
    at = end + 2;
  }
  return parts;
}

int64_t set_bits(const std::string& bytes) {
  int64_t n = 0;
  for (const char c : bytes) n += __builtin_popcount(static_cast<unsigned char>(c));
  return n;
}

TEST_F(DicomwebTest, ASegRetrievedIsTheStructuresVoxelsAndTheExportsPixels) {
  Result<v1::ImportDicomResponse> imported = client_->import_dicom({test_data("sts/STS_002/dicom/CT")});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  ASSERT_EQ(imported->structures_size(), 1);
  const v1::ImportedStructure& gtv = imported->structures(0);
  const json series = get("/dicom-web/series?Modality=SEG");
  ASSERT_EQ(series.size(), 1u);
  const std::string study = value(series[0], kStudyUid);
  const std::string seg_uid = value(series[0], kSeriesUid);
  const std::string url = "/dicom-web/studies/" + study + "/series/" + seg_uid;

  httplib::Result r = http_->Get(url.c_str(), {{"Accept", "multipart/related; type=\"application/dicom\""}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type").rfind("multipart/related; type=\"application/dicom\"", 0), 0u);
  const std::vector<std::string> parts = parts_of(r);
  ASSERT_EQ(parts.size(), 1u);
  Result<std::string> pixels = dicom::pixel_data_of(parts[0]);
  ASSERT_TRUE(pixels.ok()) << pixels.status().to_string();
  // Binary SEG frames hold one bit per voxel, padding bits zero: the set bits are the voxels inside.
  EXPECT_EQ(set_bits(*pixels), gtv.voxel_count());

  // ExportSeg (soiq export-seg) writes the same frames, under other UIDs.
  v1::ExportSegRequest req;
  req.add_structure_ids(gtv.structure().id());
  const std::string exported = dir_.file("exported.dcm");
  ASSERT_TRUE(client_->export_seg(req, exported).ok());
  std::ifstream in(exported, std::ios::binary);
  std::ostringstream file;
  file << in.rdbuf();
  EXPECT_EQ(dicom::pixel_data_of(file.str()).value(), *pixels);

  // The same SEG again has the same UIDs; by instance, by study and as bulk data too.
  const json metadata = get(url + "/metadata");
  ASSERT_EQ(metadata.size(), 1u);
  EXPECT_EQ(value(metadata[0], kSeriesUid), seg_uid);
  const std::string sop = value(metadata[0], kSopUid);
  EXPECT_EQ(sop, value(get(url + "/instances")[0], kSopUid));
  EXPECT_EQ(metadata[0]["7FE00010"]["BulkDataURI"],
            "http://127.0.0.1:" + std::to_string(server_->http_port()) + url + "/instances/" + sop + "/bulkdata");
  httplib::Result one = http_->Get((url + "/instances/" + sop).c_str());
  ASSERT_TRUE(one);
  EXPECT_EQ(one->status, 200);
  // The same object byte for byte: UIDs, dimension organization, content date and time.
  EXPECT_EQ(parts_of(one).at(0), parts[0]);
  httplib::Result whole_study = http_->Get(("/dicom-web/studies/" + study).c_str());
  ASSERT_TRUE(whole_study);
  EXPECT_EQ(parts_of(whole_study).size(), 50u);  // the CT's 48 kept instances, the SEG and the RTSTRUCT
  httplib::Result bulk = http_->Get((url + "/instances/" + sop + "/bulkdata").c_str());
  ASSERT_TRUE(bulk);
  EXPECT_EQ(parts_of(bulk).at(0), *pixels);
}

// The RT Structure Set's contours in its DICOM JSON: (ROI name, contour count) per ROI.
std::vector<std::pair<std::string, size_t>> rois_of(const json& metadata) {
  std::vector<std::pair<std::string, size_t>> out;
  const json& names = metadata["30060020"]["Value"];
  const json& contours = metadata["30060039"]["Value"];
  for (size_t i = 0; i < names.size() && i < contours.size(); ++i)
    out.emplace_back(value(names[i], "30060026"), contours[i]["30060040"]["Value"].size());
  return out;
}

TEST_F(DicomwebTest, AnRtStructureSetRetrievedIsTheStructuresContoursAsExported) {
  Result<v1::ImportDicomResponse> imported = client_->import_dicom({test_data("sts/STS_002/dicom/CT")});
  ASSERT_TRUE(imported.ok()) << imported.status().to_string();
  ASSERT_EQ(imported->structures_size(), 1);
  const v1::ImportedStructure& gtv = imported->structures(0);
  const json series = get("/dicom-web/series?Modality=RTSTRUCT");
  ASSERT_EQ(series.size(), 1u);
  const std::string study = value(series[0], kStudyUid);
  const std::string rt_uid = value(series[0], kSeriesUid);
  const std::string url = "/dicom-web/studies/" + study + "/series/" + rt_uid;
  EXPECT_NE(rt_uid, value(get("/dicom-web/series?Modality=SEG")[0], kSeriesUid));

  httplib::Result r = http_->Get(url.c_str(), {{"Accept", "multipart/related; type=\"application/dicom\""}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type").rfind("multipart/related; type=\"application/dicom\"", 0), 0u);
  const std::vector<std::string> parts = parts_of(r);
  ASSERT_EQ(parts.size(), 1u);

  // Its metadata: an RT Structure Set of the GTV, with the contours ExportRtStruct writes.
  const json metadata = get(url + "/metadata");
  ASSERT_EQ(metadata.size(), 1u);
  EXPECT_EQ(value(metadata[0], "00080060"), "RTSTRUCT");
  EXPECT_EQ(value(metadata[0], "00080016"), "1.2.840.10008.5.1.4.1.1.481.3");
  EXPECT_EQ(value(metadata[0], kSeriesUid), rt_uid);
  const std::string sop = value(metadata[0], kSopUid);
  EXPECT_EQ(sop, value(get(url + "/instances")[0], kSopUid));
  v1::ExportRtStructRequest req;
  req.add_structure_ids(gtv.structure().id());
  Result<v1::RtStructInfo> exported = client_->export_rt_struct(req, dir_.file("exported.dcm"));
  ASSERT_TRUE(exported.ok()) << exported.status().to_string();
  const auto rois = rois_of(metadata[0]);
  ASSERT_EQ(rois.size(), 1u);
  EXPECT_EQ(rois[0].first, gtv.structure().name());
  EXPECT_EQ(int64_t(rois[0].second), exported->contours());
  EXPECT_GT(exported->contours(), 0);

  // The same object byte for byte by instance, and again; the study's metadata holds it.
  httplib::Result one = http_->Get((url + "/instances/" + sop).c_str());
  ASSERT_TRUE(one);
  EXPECT_EQ(one->status, 200);
  EXPECT_EQ(parts_of(one).at(0), parts[0]);
  EXPECT_EQ(parts_of(http_->Get(url.c_str())).at(0), parts[0]);
  const json study_metadata = get("/dicom-web/studies/" + study + "/metadata");
  EXPECT_EQ(study_metadata.size(), 50u);  // the CT's 48 instances, the SEG and the RT Structure Set
  EXPECT_EQ(values(study_metadata, "00080060").back(), "RTSTRUCT");

  // What it cannot give, as the SEG's paths say it.
  get(url + "/instances/1.2.3", 404);
  get(url + "/instances/" + sop + "/frames/1", 404);
  get(url + "/instances/" + sop + "/bulkdata", 404);
  get("/dicom-web/studies/1.2.3/series/" + rt_uid, 404);
  httplib::Result other_syntax =
      http_->Get(url.c_str(),
                 {{"Accept", "multipart/related; type=\"application/dicom\"; transfer-syntax=1.2.840.10008.1.2.4.50"}});
  ASSERT_TRUE(other_syntax);
  EXPECT_EQ(other_syntax->status, 406);
}

TEST_F(DicomwebTest, WhatSoiqCannotSendIsRefusedSayingWhy) {
  ASSERT_TRUE(client_->import_dicom({test_data("sts/STS_002/dicom/CT")}).ok());
  const json series = get("/dicom-web/series");
  ASSERT_EQ(series.size(), 3u);  // the CT, then the GTV's SEG and RT Structure Set
  const std::string study = value(series[0], kStudyUid);
  const std::string ct = "/dicom-web/studies/" + study + "/series/" + value(series[0], kSeriesUid);
  const json image = get(ct + "/instances/1.2.3/metadata", 404);
  EXPECT_NE(image["error"]["message"].get<std::string>().find("instance '1.2.3' not found"), std::string::npos);
  const std::string seg = "/dicom-web/studies/" + study + "/series/" + value(series[1], kSeriesUid);
  get(seg + "/instances/1.2.3", 404);
  get("/dicom-web/studies/1.2.3/series/" + value(series[1], kSeriesUid), 404);  // another study
  get("/dicom-web/studies/" + study + "/series/2.25.1", 404);
  httplib::Result jpeg = http_->Get(seg.c_str(), {{"Accept", "multipart/related; type=\"image/jpeg\""}});
  ASSERT_TRUE(jpeg);
  EXPECT_EQ(jpeg->status, 406);
  httplib::Result other_syntax =
      http_->Get(seg.c_str(),
                 {{"Accept", "multipart/related; type=\"application/dicom\"; transfer-syntax=1.2.840.10008.1.2.4.50"}});
  ASSERT_TRUE(other_syntax);
  EXPECT_EQ(other_syntax->status, 406);
}

}  // namespace
}  // namespace soiq::testing

namespace soiq::testing {
namespace {

// SEGs written on demand are within the memory budget, from the conversion to the last byte of the
// answer: with a budget that fits two at a time, many concurrent WADO-RS retrievals and
// export-segs all succeed (they queue), the budget's peak stays under it, and nothing stays held.
TEST_F(DicomwebTest, ConcurrentSegRetrievalsAndExportsStayWithinTheBudget) {
  import("sts/STS_002/dicom/CT");
  const json series = get("/dicom-web/series?Modality=SEG");
  ASSERT_EQ(series.size(), 1u);
  const std::string url =
      "/dicom-web/studies/" + value(series[0], kStudyUid) + "/series/" + value(series[0], kSeriesUid);
  Result<v1::ListStructuresResponse> page = client_->list_structures(v1::ListStructuresRequest());
  ASSERT_TRUE(page.ok() && page->structures_size() == 1);
  const int64_t id = page->structures(0).id();
  // One SEG's peak, on a soiqd that has done nothing else (the import's peak is larger).
  start_http({"--keep-patient-names", "on"});
  ASSERT_EQ(http_->Get(url.c_str())->status, 200);
  Result<v1::ServerInfo> alone = client_->server_info();
  ASSERT_TRUE(alone.ok());
  const int64_t one = alone->memory_peak_bytes();
  ASSERT_GT(one, 0);
  const int64_t budget = 2 * one + one / 2;
  start_http({"--memory-budget", std::to_string(budget), "--workers", "4"});
  const long long rss_before = server_->peak_rss_bytes();

  constexpr int kRetrievals = 6, kExports = 3;
  std::vector<std::thread> clients;
  std::vector<std::string> failures(kRetrievals + kExports);
  for (int n = 0; n < kRetrievals; ++n) {
    clients.emplace_back([&, n] {
      httplib::Client http("127.0.0.1", server_->http_port());
      http.set_read_timeout(120, 0);
      httplib::Result r = http.Get(url.c_str());
      if (!r || r->status != 200) failures[size_t(n)] = "WADO: " + (r ? r->body : std::string("no answer"));
    });
  }
  for (int n = 0; n < kExports; ++n) {
    clients.emplace_back([&, n] {
      client::Client own = connect();
      v1::ExportSegRequest req;
      req.add_structure_ids(id);
      const Status s = own.export_seg(req, dir_.file("export" + std::to_string(n) + ".dcm")).status();
      if (!s.ok()) failures[size_t(kRetrievals + n)] = "export: " + s.to_string();
    });
  }
  for (std::thread& t : clients) t.join();
  for (const std::string& f : failures) EXPECT_EQ(f, "");
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  // Nine SEGs at once would have needed 9x one; the budget held them to at most 2.5x.
  EXPECT_LE(info->memory_peak_bytes(), budget);
  EXPECT_EQ(info->memory_in_use_bytes(), 0);
  const long long rss_after = server_->peak_rss_bytes();
#if SOIQ_TEST_UNDER_ASAN
  // ASan keeps freed blocks in quarantine: its VmHWM says nothing of soiqd's own.
  (void)rss_before;
  (void)rss_after;
#else
  EXPECT_LT(rss_after - rss_before, budget + (16ll << 20)) << "VmHWM " << rss_before << " -> " << rss_after;
#endif
}

}  // namespace
}  // namespace soiq::testing
