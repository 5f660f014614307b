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
// A named namespace, not an anonymous one: soiq-bench is a unity build, and another file's anonymous
// `note` or `percentile` would make unqualified calls from soiq::bench ambiguous. Everything,
// run() included, lives here so that lookup starts in this namespace.
namespace viewer_wado {

void note(const std::string& s) { std::fprintf(stderr, "soiq-bench viewer: %s\n", s.c_str()); }

constexpr char kFramesAccept[] = "multipart/related; type=application/octet-stream; transfer-syntax=*";
constexpr char kInstancesAccept[] = "multipart/related; type=\"application/dicom\"; transfer-syntax=*";
constexpr int kBrowserConnections = 6;  // a browser's limit per host over HTTP/1.1

struct Slice {
  std::string sop_uid, bytes;
};

struct Study {
  std::string study_uid, series_uid;
  std::vector<Slice> slices;        // the CT series, the frames asked for
  std::vector<std::string> others;  // sent too (the RTSTRUCT), as the study holds it, never timed
  size_t frame_bytes = 0;           // Rows x Columns x BitsAllocated / 8 of a native frame
};

std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// STS_002's CT as files and UIDs (DCMTK reads the UIDs; the bytes go out as they are) and its RTSTRUCT.
bool load_study(Study& out) {
  const std::string dir = std::string(SOIQ_TEST_DATA_DIR) + "/sts/STS_002/dicom/CT";
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/image")) {
    DcmFileFormat file;
    if (file.loadFile(entry.path().c_str()).bad()) return false;
    DcmDataset& ds = *file.getDataset();
    OFString sop, study, series;
    Uint16 rows = 0, columns = 0, bits = 0;
    ds.findAndGetOFString(DCM_SOPInstanceUID, sop);
    ds.findAndGetOFString(DCM_StudyInstanceUID, study);
    ds.findAndGetOFString(DCM_SeriesInstanceUID, series);
    ds.findAndGetUint16(DCM_Rows, rows);
    ds.findAndGetUint16(DCM_Columns, columns);
    ds.findAndGetUint16(DCM_BitsAllocated, bits);
    out.slices.push_back({sop.c_str(), read_bytes(entry.path())});
    out.study_uid = study.c_str();
    out.series_uid = series.c_str();
    out.frame_bytes = size_t(rows) * columns * bits / 8;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/mask"))
    out.others.push_back(read_bytes(entry.path()));
  std::sort(out.slices.begin(), out.slices.end(), [](const Slice& a, const Slice& b) { return a.sop_uid < b.sop_uid; });
  return !out.slices.empty() && out.frame_bytes > 0;
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

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

std::unique_ptr<httplib::Client> client(int port) {
  auto c = std::make_unique<httplib::Client>("127.0.0.1", port);
  c->set_keep_alive(true);
  c->set_read_timeout(120, 0);
  c->set_write_timeout(120, 0);
  return c;
}

// One server with its connections, kept over the runs as a browser keeps them open.
struct Side {
  Side(std::string n, int port) : name(std::move(n)), http(client(port)) {
    for (int i = 0; i < kBrowserConnections; ++i) pool.push_back(client(port));
  }
  std::string name;
  std::unique_ptr<httplib::Client> http;
  std::vector<std::unique_ptr<httplib::Client>> pool;
  std::vector<double> metadata_ms, frame_ms, parallel_ms, series_ms;
  int64_t metadata_items = 0, series_bytes = 0;
  std::map<std::string, std::string> frames;  // by SOP Instance UID
};

std::string series_path(const Study& study) {
  return "/dicom-web/studies/" + study.study_uid + "/series/" + study.series_uid;
}

std::string frame_path(const Study& study, const Slice& s) {
  return series_path(study) + "/instances/" + s.sop_uid + "/frames/1";
}

bool stow(Side& s, const Study& study) {
  for (int i = 0; i < 200; ++i) {  // Orthanc's HTTP comes up after its DICOM port
    httplib::Result r = s.http->Get("/dicom-web/studies?limit=1");
    if (r && r->status == 200) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::string boundary = "soiq-bench-viewer";
  std::string body;
  const auto part = [&](const std::string& bytes) {
    body += "--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n" + bytes + "\r\n";
  };
  for (const Slice& f : study.slices) part(f.bytes);
  for (const std::string& f : study.others) part(f);
  body += "--" + boundary + "--\r\n";
  httplib::Result r = s.http->Post("/dicom-web/studies", body,
                                   ("multipart/related; type=\"application/dicom\"; boundary=" + boundary).c_str());
  if (r && r->status == 200) return true;
  note(s.name + ": STOW-RS answered " + (r ? std::to_string(r->status) + " " + r->body.substr(0, 300) : "nothing"));
  return false;
}

bool time_metadata(Side& s, const Study& study) {
  const auto start = Clock::now();
  httplib::Result r = s.http->Get((series_path(study) + "/metadata").c_str(), {{"Accept", "application/dicom+json"}});
  if (!r || r->status != 200) return false;
  s.metadata_ms.push_back(ms_since(start));
  s.metadata_items = int64_t(nlohmann::json::parse(r->body, nullptr, false).size());
  return true;
}

// Each frame once, one after the other on the same keep-alive connection: one frame's latency.
bool time_frames_in_turn(Side& s, const Study& study) {
  for (const Slice& f : study.slices) {
    const auto start = Clock::now();
    httplib::Result r = s.http->Get(frame_path(study, f).c_str(), {{"Accept", kFramesAccept}});
    if (!r || r->status != 200) return false;
    s.frame_ms.push_back(ms_since(start));
    s.frames[f.sop_uid] = first_part(r);
  }
  return true;
}

// As a browser: 6 connections, each taking the next frame until all are in.
bool time_frames_at_once(Side& s, const Study& study) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  const auto start = Clock::now();
  std::vector<std::thread> threads;
  for (auto& c : s.pool)
    threads.emplace_back([&, http = c.get()] {
      for (size_t i = next++; i < study.slices.size(); i = next++) {
        httplib::Result r = http->Get(frame_path(study, study.slices[i]).c_str(), {{"Accept", kFramesAccept}});
        if (!r || r->status != 200) failed = true;
      }
    });
  for (std::thread& t : threads) t.join();
  if (failed) return false;
  s.parallel_ms.push_back(ms_since(start));
  return true;
}

bool time_series(Side& s, const Study& study) {
  const auto start = Clock::now();
  httplib::Result r = s.http->Get(series_path(study).c_str(), {{"Accept", kInstancesAccept}});
  if (!r || r->status != 200) return false;
  s.series_ms.push_back(ms_since(start));
  s.series_bytes = int64_t(r->body.size());
  return true;
}

bool run_once(Side& s, const Study& study) {
  return time_metadata(s, study) && time_frames_in_turn(s, study) && time_frames_at_once(s, study) &&
         time_series(s, study);
}

// "" when every side answered the whole series and native frames of the right size, and both sent
// the same frame bytes; else what was wrong.
std::string check(const std::vector<std::unique_ptr<Side>>& sides, const Study& study) {
  for (const auto& s : sides) {
    if (size_t(s->metadata_items) != study.slices.size())
      return s->name + "'s /metadata held " + std::to_string(s->metadata_items) + " items, not " +
             std::to_string(study.slices.size());
    for (const auto& [sop, bytes] : s->frames)
      if (bytes.size() != study.frame_bytes)
        return s->name + "'s frame of " + sop + " is " + std::to_string(bytes.size()) + " bytes, not " +
               std::to_string(study.frame_bytes);
  }
  if (sides.size() == 2 && sides[0]->frames != sides[1]->frames) return "the frames differ between the servers";
  return "";
}

void print_table(const std::vector<std::unique_ptr<Side>>& sides, const Study& study, int runs,
                 const std::string& orthanc_missing) {
  std::printf("| STS_002's CT, %zu slices, %d runs |", study.slices.size(), runs);
  for (const auto& s : sides) std::printf(" %s p50 ms | %s p95 ms |", s->name.c_str(), s->name.c_str());
  if (!orthanc_missing.empty()) std::printf(" Orthanc |");
  std::printf("\n|---|");
  for (size_t i = 0; i < sides.size(); ++i) std::printf("---:|---:|");
  if (!orthanc_missing.empty()) std::printf("---|");
  const auto row = [&](const std::string& what, std::vector<double> Side::*times) {
    std::printf("\n| %s |", what.c_str());
    for (const auto& s : sides) std::printf(" %.2f | %.2f |", percentile(*s.*times, 0.5), percentile(*s.*times, 0.95));
    if (!orthanc_missing.empty()) std::printf(" %s |", orthanc_missing.c_str());
  };
  const std::string n = std::to_string(study.slices.size());
  row("series `/metadata` (" + n + " items on each)", &Side::metadata_ms);
  row("one `/frames/1`, one keep-alive connection", &Side::frame_ms);
  row("all " + n + " frames, 6 connections at once", &Side::parallel_ms);
  row("the series' instances (`transfer-syntax=*`)", &Side::series_ms);
  std::printf("\n\n");
  for (const auto& s : sides)
    std::printf("%s's series answer: %.2f MB. ", s->name.c_str(), double(s->series_bytes) / 1e6);
  std::printf("The %s frames (%zu bytes each) %s.\n", n.c_str(), study.frame_bytes,
              sides.size() < 2 ? "were not compared (no Orthanc)" : "are the same bytes from both servers");
}

int run(const CliArgs& args) {
  Result<int> runs = args.get_int("--runs", 20);
  if (!runs.ok() || *runs < 1) {
    note("--runs takes a positive integer");
    return 2;
  }
  Study study;
  if (!load_study(study)) {
    note("cannot read STS_002's CT under tests/data/sts/STS_002/dicom/CT");
    return 1;
  }
  testing::TempDir dir;
  testing::SoiqdProcess soiqd(dir.file("soiq.db"), {"--http", "127.0.0.1:0"}, args.get("--soiqd", ""));
  if (soiqd.http_port() == 0) {
    note("soiqd did not start: " + soiqd.log());
    return 1;
  }
  std::vector<std::unique_ptr<Side>> sides;
  sides.push_back(std::make_unique<Side>("soiqd", soiqd.http_port()));
  OrthancProcess orthanc;
  std::string why = orthanc.start(true);
  if (why.empty()) sides.push_back(std::make_unique<Side>("Orthanc", orthanc.http_port()));
  if (!why.empty()) note("Orthanc left out: " + why);
  for (auto& s : sides)
    if (!stow(*s, study)) return 1;
  for (int r = 0; r < *runs; ++r)
    for (auto& s : sides)  // alternating, so both see the same machine
      if (!run_once(*s, study)) {
        note(s->name + ": a request failed in run " + std::to_string(r + 1));
        return 1;
      }
  if (const std::string wrong = check(sides, study); !wrong.empty()) {
    note(wrong);
    return 1;
  }
  print_table(sides, study, *runs, why.empty() ? "" : why.substr(0, why.find(':')));
  return 0;
}

}  // namespace viewer_wado

int run_viewer_bench(const CliArgs& args) { return viewer_wado::run(args); }

}  // namespace soiq::bench
