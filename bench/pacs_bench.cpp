#include "bench/pacs_bench.h"

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/clock.h"
#include "bench/orthanc_process.h"
#include "client/soiq_client.h"
#include "tests/support/dcmqrscp_process.h"
#include "tests/support/soiqd_process.h"

namespace soiq::bench {
namespace {

namespace fs = std::filesystem;

struct PacsOptions {
  std::string dir, patient, soiqd = SOIQD_BINARY;
  int runs = 3;
};

struct Timing {
  std::vector<double> pull_ms, push_ms;
  int64_t files = 0, bytes = 0;
};

double best(const std::vector<double>& v) { return v.empty() ? 0 : *std::min_element(v.begin(), v.end()); }
double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Sets (or, with nullptr, removes) an environment variable for the soiqd started in its scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      ::setenv(name_, old_.c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

// A fresh soiqd (its own new database) on `peer`, with Nagle's algorithm on or off.
Result<std::unique_ptr<testing::SoiqdProcess>> fresh_soiqd(const PacsOptions& o, const dicom::PacsPeer& peer,
                                                           bool nagle, const std::string& db) {
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(db + suffix);
  // soiqd turns Nagle's algorithm off unless TCP_NODELAY is set: "0" keeps it on.
  const ScopedEnv env("TCP_NODELAY", nagle ? "0" : nullptr);
  auto server = std::make_unique<testing::SoiqdProcess>(
      db, std::vector<std::string>{"--pacs", peer.called_ae + "@127.0.0.1:" + std::to_string(peer.port)}, o.soiqd);
  if (server->address().empty()) return internal_error("soiqd did not start: " + server->log());
  return server;
}

Result<client::Client> client_of(const testing::SoiqdProcess& server) {
  client::ClientOptions options;
  options.address = server.address();
  return client::Client::connect(options);
}

Result<v1::ImportDicomResponse> pull(const client::Client& c, const std::string& patient) {
  v1::PacsPullRequest request;
  request.set_patient_id(patient);
  return c.pacs_pull(request);
}

// N pulls of the patient, each into a fresh soiqd.
Status time_pulls(const PacsOptions& o, const dicom::PacsPeer& peer, bool nagle, const std::string& work, Timing& t) {
  for (int r = 0; r < o.runs; ++r) {
    SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<testing::SoiqdProcess> server,
                          fresh_soiqd(o, peer, nagle, work + "/pull.db"));
    SOIQ_ASSIGN_OR_RETURN(const client::Client c, client_of(*server));
    const Clock::time_point t0 = Clock::now();
    SOIQ_ASSIGN_OR_RETURN(const v1::ImportDicomResponse pulled, pull(c, o.patient));
    t.pull_ms.push_back(ms_since(t0));
    t.files = pulled.files_received();
    t.bytes = pulled.bytes_received();
  }
  return ok_status();
}

// N pushes of one pulled structure as a SEG. After every pull: each push adds a SEG to the PACS,
// which a later pull would fetch too.
Status time_pushes(const PacsOptions& o, const dicom::PacsPeer& peer, bool nagle, const std::string& work, Timing& t) {
  SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<testing::SoiqdProcess> server,
                        fresh_soiqd(o, peer, nagle, work + "/push.db"));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, client_of(*server));
  SOIQ_ASSIGN_OR_RETURN(const v1::ImportDicomResponse pulled, pull(c, o.patient));
  if (pulled.structures_size() == 0) return internal_error("the pull imported no structure to push");
  v1::PacsPushRequest push;
  push.add_structure_ids(pulled.structures(0).structure().id());
  push.set_series_description("soiq-bench push");
  for (int r = 0; r < o.runs; ++r) {
    const Clock::time_point t0 = Clock::now();
    SOIQ_RETURN_IF_ERROR(c.pacs_push(push).status());
    t.push_ms.push_back(ms_since(t0));
  }
  return ok_status();
}

void print_row(const std::string& pacs, const char* nagle, const Timing& t, double load_ms) {
  std::printf("| %s | %s | %lld (%.1f MB) | %.0f ms | %.0f ms | %.0f ms | %.0f ms | %.0f ms |\n", pacs.c_str(), nagle,
              (long long)t.files, double(t.bytes) / 1e6, load_ms, best(t.pull_ms), median(t.pull_ms), best(t.push_ms),
              median(t.push_ms));
}

// Loads the files into `peer` with storescu (the time it took), then the pulls both ways.
Status bench_pacs(const PacsOptions& o, const std::string& name, const dicom::PacsPeer& peer, const std::string& work) {
  std::vector<std::string> argv = {dicom::testing::find_on_path("storescu"),
                                   "-aet",
                                   "SOIQLOAD",
                                   "-aec",
                                   peer.called_ae,
                                   "+sd",
                                   "+r",
                                   "127.0.0.1",
                                   std::to_string(peer.port),
                                   o.dir};
  const Clock::time_point t0 = Clock::now();
  {
    const ScopedEnv env("TCP_NODELAY", "1");
    const int rc = dicom::testing::run_tool(argv, work + "/storescu.log");
    if (rc != 0) return internal_error("storescu exited with " + std::to_string(rc));
  }
  const double load_ms = ms_since(t0);
  Timing fast, slow;
  SOIQ_RETURN_IF_ERROR(time_pulls(o, peer, false, work, fast));
  SOIQ_RETURN_IF_ERROR(time_pulls(o, peer, true, work, slow));
  SOIQ_RETURN_IF_ERROR(time_pushes(o, peer, false, work, fast));
  SOIQ_RETURN_IF_ERROR(time_pushes(o, peer, true, work, slow));
  print_row(name, "off (soiqd's default)", fast, load_ms);
  print_row(name, "on (TCP_NODELAY=0)", slow, load_ms);
  return ok_status();
}

Status run(const PacsOptions& o) {
  const testing::TempDir work;
  std::printf(
      "| PACS | Nagle on soiq's association | files pulled | storescu load | pull best | pull median | "
      "push best | push median |\n|---|---|---:|---:|---:|---:|---:|---:|\n");
  {
    dicom::testing::DcmqrscpProcess dcmqrscp;
    const std::string why = dcmqrscp.start();
    if (!why.empty()) return internal_error("dcmqrscp: " + why);
    SOIQ_RETURN_IF_ERROR(bench_pacs(o, "DCMTK dcmqrscp 3.6.7", dcmqrscp.peer(), work.path().string()));
  }
  OrthancProcess orthanc;
  const std::string why = orthanc.start();
  if (why.rfind("not installed", 0) == 0) {
    std::printf("\n(Orthanc %s)\n", why.c_str());
    return ok_status();
  }
  if (!why.empty()) return internal_error(why);
  return bench_pacs(o, "Orthanc 1.10.1", orthanc.peer(), work.path().string());
}

}  // namespace

int run_pacs_bench(const CliArgs& args) {
  PacsOptions o;
  const std::vector<std::string>& operands = args.positional;
  Result<int> runs = args.get_int("--runs", o.runs);
  o.patient = args.get("--patient", "");
  o.soiqd = args.get("--soiqd", o.soiqd);
  if (!runs.ok() || *runs < 1 || operands.size() != 1 || o.patient.empty()) {
    std::fprintf(stderr, "usage: soiq-bench pacs DICOM_DIR --patient ID [--runs N] [--soiqd PATH]\n");
    return 2;
  }
  o.runs = *runs;
  o.dir = operands[0];
  const Status s = run(o);
  if (!s.ok()) {
    std::fprintf(stderr, "soiq-bench pacs: %s\n", s.to_string().c_str());
    return 1;
  }
  return 0;
}

}  // namespace soiq::bench
