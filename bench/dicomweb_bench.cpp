#include "bench/dicomweb_bench.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dcostrmb.h>
#include <dcmtk/dcmdata/dctk.h>
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench/clock.h"
#include "bench/orthanc_process.h"
#include "dicom/dcmtk_file.h"
#include "tests/support/soiqd_process.h"
#include "tests/support/temp_dir.h"

namespace soiq::bench {
namespace {

void note(const std::string& s) { std::fprintf(stderr, "soiq-bench dicomweb: %s\n", s.c_str()); }
// "2.25.<n>" UIDs of the synthetic data: kind 1 study, 2 series, 3 instance, 4 frame of reference.
std::string uid(int kind, int n) { return "2.25." + std::to_string(kind) + std::to_string(1000000000 + n); }

std::string patient_id(int n) {
  char id[16];
  std::snprintf(id, sizeof id, "DW%06d", n);
  return id;
}

std::string study_date(int n) {
  // Spread over 2000-2019: month and day (1-28) from n, so a month holds ~N/240 studies.
  char d[16];
  std::snprintf(d, sizeof d, "%04d%02d%02d", 2000 + (n / 12) % 20, 1 + n % 12, 1 + (n / 240) % 28);
  return d;
}

// One patient's instance as a Part 10 file in memory.
std::optional<std::string> instance(DcmFileFormat& file, int n) {
  DcmDataset& ds = *file.getDataset();
  const std::string pid = patient_id(n);
  const std::string name = "Synthetic^" + pid + (n % 2 ? "^Anna" : "^John");
  const std::string sop = uid(3, n);
  bool ok = ds.putAndInsertString(DCM_PatientID, pid.c_str()).good() &&
            ds.putAndInsertString(DCM_PatientName, name.c_str()).good() &&
            ds.putAndInsertString(DCM_PatientSex, n % 2 ? "F" : "M").good() &&
            ds.putAndInsertString(DCM_PatientBirthDate, ("19" + std::to_string(30 + n % 60) + "0615").c_str()).good() &&
            ds.putAndInsertString(DCM_StudyDate, study_date(n).c_str()).good() &&
            ds.putAndInsertString(DCM_StudyInstanceUID, uid(1, n).c_str()).good() &&
            ds.putAndInsertString(DCM_SeriesInstanceUID, uid(2, n).c_str()).good() &&
            ds.putAndInsertString(DCM_FrameOfReferenceUID, uid(4, n).c_str()).good() &&
            ds.putAndInsertString(DCM_SOPInstanceUID, sop.c_str()).good() &&
            ds.putAndInsertString(DCM_AccessionNumber, ("A" + std::to_string(n)).c_str()).good() &&
            file.getMetaInfo()->putAndInsertString(DCM_MediaStorageSOPInstanceUID, sop.c_str()).good();
  if (!ok) return std::nullopt;
  Result<std::string> bytes = dicom::part10_bytes(file);
  if (!bytes.ok()) return std::nullopt;
  return std::move(*bytes);
}

// CT_small.dcm's header with 16 x 16 pixels.
bool load_template(DcmFileFormat& file) {
  if (file.loadFile((std::string(SOIQ_TEST_DATA_DIR) + "/dicom/CT_small.dcm").c_str()).bad()) return false;
  DcmDataset& ds = *file.getDataset();
  std::vector<Uint16> pixels(16 * 16);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = Uint16(i * 7 % 512);
  return ds.putAndInsertUint16(DCM_Rows, 16).good() && ds.putAndInsertUint16(DCM_Columns, 16).good() &&
         ds.putAndInsertUint16Array(DCM_PixelData, pixels.data(), pixels.size()).good();
}

struct Server {
  Server(std::string n, std::unique_ptr<httplib::Client> h) : name(std::move(n)), http(std::move(h)) {}
  std::string name;
  std::unique_ptr<httplib::Client> http;
  double stow_s = 0;
  int64_t stored = 0;
  std::vector<std::vector<double>> latencies;  // by query
  std::vector<int64_t> rows;                   // by query
};

// POSTs the instances in requests of `batch`; false on the first refused one.
bool stow(Server& s, const std::vector<std::string>& instances, int batch) {
  const auto start = Clock::now();
  for (size_t from = 0; from < instances.size(); from += size_t(batch)) {
    const std::string boundary = "soiq-bench-boundary";
    std::string body;
    const size_t to = std::min(instances.size(), from + size_t(batch));
    for (size_t i = from; i < to; ++i)
      body += "--" + boundary + "\r\nContent-Type: application/dicom\r\n\r\n" + instances[i] + "\r\n";
    body += "--" + boundary + "--\r\n";
    httplib::Result r = s.http->Post("/dicom-web/studies", body,
                                     ("multipart/related; type=\"application/dicom\"; boundary=" + boundary).c_str());
    if (!r || r->status != 200) {
      note(s.name + ": STOW-RS answered " + (r ? std::to_string(r->status) + " " + r->body.substr(0, 300) : "nothing"));
      return false;
    }
    s.stored += int64_t(to - from);
  }
  s.stow_s = ms_since(start) / 1000;
  return true;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

}  // namespace

int run_dicomweb_bench(const CliArgs& args) {
  Result<int> patients = args.get_int("--patients", 100000);
  Result<int> batch = args.get_int("--batch", 100);
  Result<int> runs = args.get_int("--runs", 50);
  if (!patients.ok() || !batch.ok() || !runs.ok() || *patients < 1000 || *batch < 1 || *runs < 1) {
    note("--patients (>= 1000), --batch and --runs take positive integers");
    return 2;
  }
  const int n = *patients;
  note("writing " + std::to_string(n) + " synthetic instances");
  DcmFileFormat file;
  if (!load_template(file)) {
    note("cannot read tests/data/dicom/CT_small.dcm");
    return 1;
  }
  std::vector<std::string> instances;
  instances.reserve(size_t(n));
  for (int i = 1; i <= n; ++i) {
    std::optional<std::string> bytes = instance(file, i);
    if (!bytes) {
      note("DCMTK could not write instance " + std::to_string(i));
      return 1;
    }
    instances.push_back(std::move(*bytes));
  }

  testing::TempDir dir;
  testing::SoiqdProcess soiqd(
      dir.file("soiq.db"), {"--http", "127.0.0.1:0", "--keep-patient-names", "on", "--max-upload-bytes", "1073741824"},
      args.get("--soiqd", ""));
  if (soiqd.http_port() == 0) {
    note("soiqd did not start: " + soiqd.log());
    return 1;
  }
  std::vector<Server> servers;
  servers.emplace_back("soiqd", std::make_unique<httplib::Client>("127.0.0.1", soiqd.http_port()));
  OrthancProcess orthanc;
  const std::string why = orthanc.start(true);
  if (why.empty()) {
    servers.emplace_back("Orthanc", std::make_unique<httplib::Client>("127.0.0.1", orthanc.http_port()));
  } else {
    note("Orthanc left out: " + why);
  }
  for (Server& s : servers) {
    s.http->set_read_timeout(600, 0);
    s.http->set_write_timeout(600, 0);
    s.http->set_keep_alive(true);
    for (int i = 0; i < 200; ++i) {  // Orthanc's HTTP comes up after its DICOM port
      httplib::Result r = s.http->Get("/dicom-web/studies?limit=1");
      if (r && r->status == 200) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    note("STOW-RS into " + s.name);
    if (!stow(s, instances, *batch)) return 1;
  }

  // The study queries, in DICOM's words; each server answers them over the same data.
  const std::string month = study_date(n / 2).substr(0, 6);
  const std::string one_id = patient_id(n / 3);
  const std::vector<std::pair<std::string, std::string>> queries = {
      {"first page (limit=100)", "/dicom-web/studies?limit=100"},
      {"PatientID prefix (DW0123*)", "/dicom-web/studies?PatientID=DW0123*"},
      {"StudyDate, one month (limit=100)", "/dicom-web/studies?StudyDate=" + month + "01-" + month + "28&limit=100"},
      // No '^' in the value: Orthanc 1.10 with DICOMweb 1.7 matches no PatientName holding one, not
      // even an exact name (0 rows where soiqd had 100 in the first run).
      {"PatientName wildcard (synthetic*dw0456*)", "/dicom-web/studies?PatientName=synthetic*dw0456*"},
      {"one StudyInstanceUID", "/dicom-web/studies?StudyInstanceUID=" + uid(1, n / 3)},
      {"deep page (offset=" + std::to_string(n / 2) + ", limit=100)",
       "/dicom-web/studies?offset=" + std::to_string(n / 2) + "&limit=100"},
  };
  for (Server& s : servers) {
    note("QIDO-RS on " + s.name);
    s.latencies.assign(queries.size(), {});
    s.rows.assign(queries.size(), -1);
    for (int r = 0; r < *runs; ++r) {
      for (size_t q = 0; q < queries.size(); ++q) {
        const auto start = Clock::now();
        httplib::Result res = s.http->Get(queries[q].second.c_str());
        const double ms = ms_since(start);
        if (!res || res->status != 200) {
          note(s.name + ": " + queries[q].second + " answered " + (res ? std::to_string(res->status) : "nothing"));
          return 1;
        }
        s.latencies[q].push_back(ms);
        if (r == 0) s.rows[q] = int64_t(nlohmann::json::parse(res->body, nullptr, false).size());
      }
    }
  }

  std::printf("| STOW-RS, %d instances in requests of %d | seconds | instances/s |\n|---|---:|---:|\n", n, *batch);
  for (const Server& s : servers)
    std::printf("| %s | %.1f | %.0f |\n", s.name.c_str(), s.stow_s, double(s.stored) / s.stow_s);
  std::printf("\n| QIDO-RS study query, %d studies, %d runs |", n, *runs);
  for (const Server& s : servers) std::printf(" %s p50 ms | %s p95 ms | rows |", s.name.c_str(), s.name.c_str());
  std::printf("\n|---|");
  for (size_t i = 0; i < servers.size(); ++i) std::printf("---:|---:|---:|");
  std::printf("\n");
  for (size_t q = 0; q < queries.size(); ++q) {
    std::printf("| %s |", queries[q].first.c_str());
    for (const Server& s : servers)
      std::printf(" %.2f | %.2f | %lld |", percentile(s.latencies[q], 0.5), percentile(s.latencies[q], 0.95),
                  (long long)s.rows[q]);
    std::printf("\n");
  }
  return 0;
}

}  // namespace soiq::bench
