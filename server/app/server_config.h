#pragma once
// soiqd's configuration: flags, with environment variables as defaults (flags win), so the same
// binary runs from a shell, from `make run` and in a container.
//
//   flag                        environment                default
//   --listen HOST:PORT          SOIQ_LISTEN                127.0.0.1:50051 (port 0: any free port)
//   --db PATH                   SOIQ_DB                    var/soiq.db
//   --port-file PATH            SOIQ_PORT_FILE             none; the bound port is written there
//   --max-upload-bytes N        SOIQ_MAX_UPLOAD_BYTES      268435456 (256 MiB)
//   --max-grid-voxels N         SOIQ_MAX_GRID_VOXELS       500000000
//   --memory-budget BYTES       SOIQ_MEMORY_BUDGET         half the RAM (or of the cgroup's memory.max):
//                                                          the peak bytes all conversions and features
//                                                          may hold at once (8G, 512M, or bytes)
//   --workers N                 SOIQ_WORKERS               hardware threads (concurrent conversions)
//   --query-result-cap N        SOIQ_QUERY_RESULT_CAP      10000 rows
//   --stage1-cap N              SOIQ_STAGE1_CAP            100000 candidate structures
//   --tls-cert PEM --tls-key PEM SOIQ_TLS_CERT/SOIQ_TLS_KEY none (plaintext)
//   --token-file PATH           SOIQ_TOKEN_FILE            none (no authentication)
//   --pacs AE@HOST:PORT         SOIQ_PACS                  none (the Pacs* calls are refused)
//   --pacs-calling-ae AE        SOIQ_PACS_CALLING_AE       SOIQ (soiq's AE title towards the PACS)
//   --pacs-timeout SECONDS      SOIQ_PACS_TIMEOUT          30 (connect, each association and DIMSE message)
//
// Errors: INVALID_ARGUMENT naming the flag or variable and what it accepts.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::server {

struct ServerConfig {
  std::string listen = "127.0.0.1:50051";
  std::string db_path = "var/soiq.db";
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
  std::optional<dicom::PacsPeer> pacs_peer;  // parsed from the three above; nullopt without --pacs
};

// `getenv` is injectable for tests; `help` is set when --help was given.
Result<ServerConfig> parse_server_config(int argc, char** argv, bool& help,
                                         const std::function<const char*(const char*)>& getenv);

const char* server_usage();

}  // namespace soiq::server
