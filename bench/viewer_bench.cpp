#include "bench/viewer_bench.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench/clock.h"
#include "bench/orthanc_process.h"
#include "tests/support/soiqd_process.h"
#include "tests/support/temp_dir.h"

namespace soiq::bench {
// A named namespace: soiq-bench is a unity build, and dicomweb_bench.cpp's helpers have these names.
namespace viewer_wado {

void note(const std::string& s) { std::fprintf(stderr, "soiq-bench viewer: %s\n", s.c_str()); }

constexpr char kFramesAccept[] = "multipart/related; type=application/octet-stream; transfer-syntax=*";
constexpr char kInstancesAccept[] = "multipart/related; type=\"application/dicom\"; transfer-syntax=*";
constexpr int kBrowserConnections = 6;

struct CtFile {
  std::string sop_uid, bytes;
};

struct Study {
  std::string study_uid, series_uid;
  std::vector<CtFile> files;
};

// STS_002's CT as files and UIDs (DCMTK reads the UIDs; the bytes go out as they are).
bool load_ct(Study& out) {
  const std::string dir = std::string(SOIQ_TEST_DATA_DIR) + "/sts/STS_002/dicom/CT/image";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    DcmFileFormat file;
    if (file.loadFile(entry.path().c_str()).bad()) return false;
    OFString sop, study, series;
    file.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, sop);
    file.getDataset()->findAndGetOFString(DCM_StudyInstanceUID, study);
    file.getDataset()->findAndGetOFString(DCM_SeriesInstanceUID, series);
    std::ifstream in(entry.path(), std::ios::binary);
    out.files.push_back({sop.c_str(), std::string(std::istreambuf_iterator<char>(in), {})});
    out.study_uid = study.c_str();
    out.series_uid = series.c_str();
  }
  std::sort(out.files.begin(), out.files.end(), [](const CtFile& a, const CtFile& b) { return a.sop_uid < b.sop_uid; });
  return !out.files.empty();
}

// The first part of a multipart/related answer (a reader of its own: the servers' are measured).
std::string first_part(const httplib::Result& r) {
  const std::string type = r->get_header_value("Content-Type");
  const size_t at = type.find("boundary=");
  if (at == std::string::npos) return "";
  std::string boundary = type.substr(at + 9);
  boundary = boundary.substr(0, boundary.find(';'));
  if (!boundary.empty() && boundary.front() == '"') boundary = boundary.substr(1, boundary.size() - 2);
  const size_t start = r->body.find("\r\n\r\n", r->body.find("--" + boundary));
  const size_t end = r->body.find("\r\n--" + boundary, start);
  if (start == std::string::npos || end == std::string::npos) return "";
  return r->body.substr(start + 4, end - start - 4);
}

double pct(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

struct Side {
  std::string name;
  int port = 0;
  std::vector<double> metadata_ms, frame_ms, parallel_ms, series_ms;
  int64_t metadata_items = 0, series_bytes = 0;
  std::map<std::string, std::string> frames;  // by SOP Instance UID
};

std::unique_ptr<httplib::Client> client(int port) {
  auto c = std::make_unique<httplib::Client>("127.0.0.1", port);
  c->set_keep_alive(true);
  c->set_read_timeout(120, 0);
  return c;
}

bool stow(const Side& s, const Study& study) {
  const std::string boundary = "soiq-bench-viewer";
  std::string body;
  for (const CtFile& f : study.files)
    body += "--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n" + f.bytes + "\r\n";
  body += "--" + boundary + "--\r\n";
  auto c = client(s.port);
  for (int i = 0; i < 200; ++i) {  // Orthanc's HTTP comes up after its DICOM port
    httplib::Result r = c->Get("/dicom-web/studies?limit=1");
    if (r && r->status == 200) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  httplib::Result r = c->Post("/dicom-web/studies", body,
                              ("multipart/related; type=\"application/dicom\"; boundary=" + boundary).c_str());
  if (r && r->status == 200) return true;
  note(s.name + ": STOW-RS answered " + (r ? std::to_string(r->status) + " " + r->body.substr(0, 300) : "nothing"));
  return false;
}

// One run of everything on one server; false when a request fails.
bool run_once(Side& s, const Study& study) {
  const std::string series = "/dicom-web/studies/" + study.study_uid + "/series/" + study.series_uid;
  auto c = client(s.port);
  auto start = Clock::now();
  httplib::Result meta = c->Get((series + "/metadata").c_str(), {{"Accept", "application/dicom+json"}});
  if (!meta || meta->status != 200) return false;
  s.metadata_ms.push_back(ms_since(start));
  s.metadata_items = int64_t(nlohmann::json::parse(meta->body, nullptr, false).size());
  for (const CtFile& f : study.files) {
    start = Clock::now();
    httplib::Result r = c->Get((series + "/instances/" + f.sop_uid + "/frames/1").c_str(), {{"Accept", kFramesAccept}});
    if (!r || r->status != 200) return false;
    s.frame_ms.push_back(ms_since(start));
    s.frames[f.sop_uid] = first_part(r);
  }
  // As a browser: 6 connections, each taking the next frame until all 48 are in.
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  start = Clock::now();
  std::vector<std::thread> pool;
  for (int k = 0; k < kBrowserConnections; ++k)
    pool.emplace_back([&] {
      auto own = client(s.port);
      for (size_t i = next++; i < study.files.size(); i = next++) {
        httplib::Result r = own->Get((series + "/instances/" + study.files[i].sop_uid + "/frames/1").c_str(),
                                     {{"Accept", kFramesAccept}});
        if (!r || r->status != 200) failed = true;
      }
    });
  for (std::thread& t : pool) t.join();
  if (failed) return false;
  s.parallel_ms.push_back(ms_since(start));
  start = Clock::now();
  httplib::Result all = c->Get(series.c_str(), {{"Accept", kInstancesAccept}});
  if (!all || all->status != 200) return false;
  s.series_ms.push_back(ms_since(start));
  s.series_bytes = int64_t(all->body.size());
  return true;
}

}  // namespace viewer_wado

int run_viewer_bench(const CliArgs& args) {
  using namespace viewer_wado;
  Result<int> runs = args.get_int("--runs", 20);
  if (!runs.ok() || *runs < 1) {
    note("--runs takes a positive integer");
    return 2;
  }
  Study study;
  if (!load_ct(study)) {
    note("cannot read STS_002's CT under tests/data/sts/STS_002/dicom/CT/image");
    return 1;
  }
  testing::TempDir dir;
  testing::SoiqdProcess soiqd(dir.file("soiq.db"), {"--http", "127.0.0.1:0"}, args.get("--soiqd", ""));
  if (soiqd.http_port() == 0) {
    note("soiqd did not start: " + soiqd.log());
    return 1;
  }
  std::vector<Side> sides;
  sides.push_back({"soiqd", soiqd.http_port()});
  OrthancProcess orthanc;
  const std::string why = orthanc.start(true);
  if (why.empty()) {
    sides.push_back({"Orthanc", orthanc.http_port()});
  } else {
    note("Orthanc left out: " + why);
  }
  for (Side& s : sides)
    if (!stow(s, study)) return 1;
  for (int r = 0; r < *runs; ++r)
    for (Side& s : sides)  // alternating, so both see the same machine
      if (!run_once(s, study)) {
        note(s.name + ": a request failed in run " + std::to_string(r + 1));
        return 1;
      }
  const bool same = sides.size() < 2 || sides[0].frames == sides[1].frames;
  std::printf("| STS_002's CT, 48 slices of 161 x 143, %d runs |", *runs);
  for (const Side& s : sides) std::printf(" %s p50 ms | %s p95 ms |", s.name.c_str(), s.name.c_str());
  std::printf("\n|---|");
  for (size_t i = 0; i < sides.size(); ++i) std::printf("---:|---:|");
  const auto row = [&](const char* what, std::vector<double> Side::*times) {
    std::printf("\n| %s |", what);
    for (const Side& s : sides) std::printf(" %.2f | %.2f |", pct(s.*times, 0.5), pct(s.*times, 0.95));
  };
  row("series `/metadata` (48 instances)", &Side::metadata_ms);
  row("one `/frames/1`, one client", &Side::frame_ms);
  row("all 48 frames, 6 connections at once", &Side::parallel_ms);
  row("the series' instances (`transfer-syntax=*`)", &Side::series_ms);
  std::printf("\n\n");
  for (const Side& s : sides)
    std::printf("%s: %lld metadata items, series answer %lld bytes. ", s.name.c_str(), (long long)s.metadata_items,
                (long long)s.series_bytes);
  std::printf("The 48 frames %s.\n", sides.size() < 2 ? "were not compared (no Orthanc)"
                                     : same           ? "are the same bytes from both servers"
                                                      : "DIFFER between the servers");
  if (!same) note("the frames differ between soiqd and Orthanc");
  return same ? 0 : 1;
}

}  // namespace soiq::bench
