#include "server/app/server_config.h"

#include <cctype>
#include <charconv>
#include <thread>

#include "core/voxelize/memory_estimate.h"
#include "server/app/pacs_address.h"

namespace soiq::server {
namespace {

Result<int64_t> parse_count(const std::string& text, const std::string& what, int64_t lo, int64_t hi) {
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    return invalid_argument(what + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                            "], got '" + text + "'");
  return v;
}

// One option: its flag, its environment variable and where its value goes.
struct Option {
  const char* flag;
  const char* env;
  std::function<Status(const std::string& value, const std::string& what)> set;
};

}  // namespace

const char* server_usage() {
  return "usage: soiqd [--listen HOST:PORT] [--db PATH] [--port-file PATH] [--max-upload-bytes N]\n"
         "             [--max-grid-voxels N] [--memory-budget BYTES] [--workers N] [--query-result-cap N]\n"
         "             [--stage1-cap N]\n"
         "             [--tls-cert PEM --tls-key PEM] [--token-file PATH]\n"
         "             [--pacs AE@HOST:PORT [--pacs-calling-ae AE] [--pacs-timeout SECONDS]]\n"
         "Every flag has an environment default: SOIQ_LISTEN, SOIQ_DB, SOIQ_PORT_FILE, SOIQ_MAX_UPLOAD_BYTES,\n"
         "SOIQ_MAX_GRID_VOXELS, SOIQ_MEMORY_BUDGET, SOIQ_WORKERS, SOIQ_QUERY_RESULT_CAP, SOIQ_STAGE1_CAP, "
         "SOIQ_TLS_CERT,\n"
         "SOIQ_TLS_KEY, SOIQ_TOKEN_FILE, SOIQ_PACS, SOIQ_PACS_CALLING_AE, SOIQ_PACS_TIMEOUT. Port 0 binds any free "
         "port (see --port-file).\n";
}

Result<ServerConfig> parse_server_config(int argc, char** argv, bool& help,
                                         const std::function<const char*(const char*)>& getenv) {
  ServerConfig c;
  help = false;
  auto count = [](auto& field, int64_t lo, int64_t hi) {
    return [&field, lo, hi](const std::string& v, const std::string& what) -> Status {
      SOIQ_ASSIGN_OR_RETURN(int64_t n, parse_count(v, what, lo, hi));
      field = static_cast<std::remove_reference_t<decltype(field)>>(n);
      return ok_status();
    };
  };
  auto text = [](std::string& field) {
    return [&field](const std::string& v, const std::string& what) -> Status {
      if (v.empty()) return invalid_argument(what + " must not be empty");
      field = v;
      return ok_status();
    };
  };
  const Option options[] = {
      {"--listen", "SOIQ_LISTEN", text(c.listen)},
      {"--db", "SOIQ_DB", text(c.db_path)},
      {"--port-file", "SOIQ_PORT_FILE", text(c.port_file)},
      {"--max-upload-bytes", "SOIQ_MAX_UPLOAD_BYTES", count(c.max_upload_bytes, 1, int64_t(1) << 40)},
      {"--max-grid-voxels", "SOIQ_MAX_GRID_VOXELS", count(c.max_grid_voxels, 1, int64_t(1) << 40)},
      {"--memory-budget", "SOIQ_MEMORY_BUDGET",
       [&c](const std::string& v, const std::string& what) -> Status {
         SOIQ_ASSIGN_OR_RETURN(c.memory_budget_bytes, parse_byte_size(v, what));
         return ok_status();
       }},
      {"--workers", "SOIQ_WORKERS", count(c.workers, 1, 1024)},
      {"--query-result-cap", "SOIQ_QUERY_RESULT_CAP", count(c.query_result_cap, 1, 10'000'000)},
      {"--stage1-cap", "SOIQ_STAGE1_CAP", count(c.stage1_cap, 1, 100'000'000)},
      {"--tls-cert", "SOIQ_TLS_CERT", text(c.tls_cert)},
      {"--tls-key", "SOIQ_TLS_KEY", text(c.tls_key)},
      {"--token-file", "SOIQ_TOKEN_FILE", text(c.token_file)},
      {"--pacs", "SOIQ_PACS", text(c.pacs)},
      {"--pacs-calling-ae", "SOIQ_PACS_CALLING_AE", text(c.pacs_calling_ae)},
      {"--pacs-timeout", "SOIQ_PACS_TIMEOUT", count(c.pacs_timeout_seconds, 1, 3600)},
  };
  for (const Option& o : options) {
    if (const char* v = getenv(o.env)) SOIQ_RETURN_IF_ERROR(o.set(v, std::string("environment variable ") + o.env));
  }
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      return c;
    }
    const Option* match = nullptr;
    std::string value;
    for (const Option& o : options) {
      const std::string flag = o.flag;
      if (arg == flag) {
        if (i + 1 >= argc) return invalid_argument(flag + " needs a value");
        value = argv[++i];
        match = &o;
      } else if (arg.rfind(flag + "=", 0) == 0) {
        value = arg.substr(flag.size() + 1);
        match = &o;
      }
      if (match) break;
    }
    if (!match) return invalid_argument("unknown option '" + arg + "'");
    SOIQ_RETURN_IF_ERROR(match->set(value, match->flag));
  }
  if (c.tls_cert.empty() != c.tls_key.empty())
    return invalid_argument("--tls-cert and --tls-key go together: give both or neither");
  if (!c.pacs.empty()) {
    Result<dicom::PacsPeer> peer = parse_pacs_address(c.pacs, c.pacs_calling_ae, c.pacs_timeout_seconds);
    if (!peer.ok()) return invalid_argument("--pacs: " + peer.status().message());
    c.pacs_peer = *peer;
  }
  if (c.memory_budget_bytes == 0) c.memory_budget_bytes = default_memory_budget_bytes();
  if (c.workers == 0) c.workers = std::max(1u, std::thread::hardware_concurrency());
  return c;
}

}  // namespace soiq::server
