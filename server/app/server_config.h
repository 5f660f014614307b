#pragma once
// soiqd's configuration: flags, with environment variables as defaults (flags win), so the same
// binary runs from a shell, from `make run` and in a container. Each flag's value, default and
// variable (SOIQ_ and the flag's name: --max-grid-voxels is SOIQ_MAX_GRID_VOXELS) are described
// once, in server_config.cpp's table, which `soiqd --help` and soiqd(8) print.
//
// Errors: INVALID_ARGUMENT naming the flag or variable and what it accepts.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::server {

struct ServerConfig {
  std::string listen = "127.0.0.1:50051";
  std::string db_path = "var/soiq.db";  // or sqlite:PATH, postgresql://… (store_location.h)
  int db_connections = 0;               // PostgreSQL's pool; 0: the workers + 4
  std::string port_file;
  int64_t max_upload_bytes = 256ll << 20;
  int64_t max_grid_voxels = 500'000'000;
  int64_t memory_budget_bytes = 0;  // 0 before parsing: the default (half the RAM)
  int workers = 0;                  // 0: hardware threads
  int query_result_cap = 10000;
  int64_t stage1_cap = 100000;
  std::string tls_cert, tls_key;
  std::string token_file;
  std::string pacs;  // AE@HOST:PORT as given
  std::string pacs_calling_ae = "SOIQ";
  int pacs_timeout_seconds = 30;
  bool precompute = true;  // compute every structure's default features in the background
  // With precompute, also its coverage-weighted features (--precompute weighted; precompute_worker.h).
  bool precompute_weighted = false;
  // DICOMweb (server/http/): "" serves none; HOST:PORT, port 0 any free one (see http_port_file).
  std::string http_listen;
  std::string http_port_file;
  // A request's head must arrive whole, and a body or an answer may not stall, within this.
  int http_timeout_seconds = 20;
  int http_max_connections = 256;  // more are answered 503 and closed
  // Patient names from DICOM are stored (and answered by QIDO-RS) only when true.
  bool keep_patient_names = false;
  // Each imported image series' original DICOM files are stored with it, for WADO-RS
  // (server/app/kept_instances.h); off for a store that must not duplicate a PACS.
  bool keep_instances = true;
  // DICOMweb answers carry CORS headers for this origin (scheme://host[:port], or "*"), and its
  // preflights are answered, so a web viewer served from there reads soiqd; "": no CORS.
  std::string http_cors_origin;
  // The query page's link to a viewer: a URL with "{study}" for the Study Instance UID and
  // optionally "{seg_series}" for the structure's SEG series; "": none.
  std::string viewer_url;
  // Replicas on a shared database (PostgreSQL; shared_stage2.h). share_stage2 is set by soiqd from
  // the store's kind, not a flag: a SQLite file has one soiqd.
  std::string replica_id;  // "": default_replica_id()
  int64_t replica_live_ms = 3000;
  bool share_stage2 = false;
  std::optional<dicom::PacsPeer> pacs_peer;  // parsed from the three above; nullopt without --pacs
};

// `getenv` is injectable for tests; `help` is set when --help was given.
Result<ServerConfig> parse_server_config(int argc, char** argv, bool& help,
                                         const std::function<const char*(const char*)>& getenv);

// `soiqd --help`: each option with its value, meaning, default and environment variable; soiqd(8)
// is made from it in the build.
const char* server_usage();

// The flags soiqd takes, in the order server_usage() describes them.
std::vector<std::string> server_option_flags();

}  // namespace soiq::server
