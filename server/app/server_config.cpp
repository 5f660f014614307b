#include "server/app/server_config.h"

#include <cctype>
#include <charconv>
#include <map>
#include <string_view>
#include <thread>
#include <vector>

#include "core/base/did_you_mean.h"
#include "core/base/field_rules.h"
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

// Every option soiqd takes, as --help and soiqd(8) describe it and in that order; the parser
// reads its flags from here (and each one's variable, env_of), so help and parser cannot differ.
struct OptionText {
  const char* flag;
  const char* value;
  const char* default_text;
  const char* meaning;
};

constexpr OptionText kOptionTexts[] = {
    {"--listen", "HOST:PORT", "127.0.0.1:50051", "where to listen; port 0 binds any free port (see --port-file)"},
    {"--db", "PATH|sqlite:PATH|postgresql://USER@HOST:PORT/DB", "var/soiq.db",
     "the store: a SQLite file (made, with its folder, when missing), or a PostgreSQL database that "
     "several soiqd replicas may share (the password from PGPASSWORD or ~/.pgpass)"},
    {"--db-connections", "N", "the workers + 4", "PostgreSQL connections this soiqd opens (the pool)"},
    {"--replica-id", "ID", "host-pid-random",
     "this soiqd's name among the replicas sharing a PostgreSQL database (at most 64 bytes)"},
    {"--replica-timeout-ms", "MS", "3000",
     "a replica silent this long is dead and its share of a query is done by the others"},
    {"--port-file", "PATH", "none", "write the bound port there once soiqd serves"},
    {"--max-upload-bytes", "N", "268435456 (256 MiB)", "the largest upload or import soiqd accepts"},
    {"--max-grid-voxels", "N", "500000000", "the largest grid of a conversion or an image"},
    {"--memory-budget", "BYTES", "half the RAM, the cgroup's limit or what ulimit -v/-d leave",
     "the peak bytes all conversions, features, imports, uploads and SEGs being written or sent may hold at "
     "once, with a quarter (at most 2G) of it for decoded surfaces and images (8G, 512M or bytes)"},
    {"--workers", "N", "the hardware threads", "conversions and feature computations at once"},
    {"--query-result-cap", "N", "10000", "the most rows one query returns"},
    {"--stage1-cap", "N", "100000", "the most candidate structures stage 1 of a query may select"},
    {"--tls-cert", "PEM", "none (plaintext)", "serve TLS with this certificate chain (with --tls-key)"},
    {"--tls-key", "PEM", "none", "the private key of --tls-cert"},
    {"--token-file", "PATH", "none (no authentication)",
     "require 'authorization: Bearer TOKEN' with the token in PATH"},
    {"--pacs", "AE@HOST:PORT", "none (the pacs calls are refused)", "the PACS of soiq pacs echo, find, pull and push"},
    {"--pacs-calling-ae", "AE", "SOIQ", "soiqd's AE title towards the PACS"},
    {"--pacs-timeout", "SECONDS", "30", "the PACS's connect, association and message timeout"},
    {"--precompute", "on|weighted|off", "on",
     "compute every new structure's default features in the background, at nice 19, so that "
     "queries read them and stage 1 filters on them; weighted: also its coverage-weighted features "
     "(volume_w_mm3, mean_w, ... inside, on every image), a coverage conversion each (about 4x a plain "
     "one); turned on, it queues again the structures precomputed without them"},
    {"--http", "HOST:PORT", "none (no DICOMweb)",
     "also serve DICOMweb (QIDO-RS, WADO-RS, STOW-RS) and soiq's JSON queries there, with the same TLS "
     "and token; port 0 binds any free port (see --http-port-file)"},
    {"--http-port-file", "PATH", "none", "write the bound DICOMweb port there once soiqd serves"},
    {"--http-timeout", "SECONDS", "20",
     "an HTTP request's head must arrive whole within this, and its body or its answer may not stall "
     "longer (then 408, or the connection closes)"},
    {"--http-max-connections", "N", "256",
     "HTTP connections served at once; more are answered 503 and closed (each holds at most 64 KiB "
     "until its token is checked)"},
    {"--keep-patient-names", "on|off", "off",
     "store the Patient's Name of imported DICOM (QIDO-RS answers and matches it); off: names are "
     "dropped at import"},
    {"--keep-instances", "on|off", "on",
     "store each imported image series' original DICOM files (deduplicated by content) so WADO-RS "
     "serves its instances, metadata and frames and a viewer opens it from soiqd; off: a PACS keeps "
     "them, and soiqd's WADO-RS serves only SEGs"},
    {"--http-cors-origin", "ORIGIN|*", "none",
     "answer DICOMweb and the JSON API with CORS headers for this origin (http(s)://HOST[:PORT]), and "
     "their preflights, so a web viewer served from there (OHIF) reads soiqd; the token is still needed"},
    {"--viewer-url", "URL", "",
     "the query page's 'open in viewer' link: an http(s) URL with {study} where the Study Instance UID "
     "goes and optionally {seg_series}, the structure's SEG series (OHIF: "
     "http://HOST:3000/viewer?StudyInstanceUIDs={study} and &initialSeriesInstanceUID={seg_series} to show "
     "the SEG); unset: no link"},
};

// scheme://host[:port] as a browser's Origin header names a site: no path, no user, no query.
bool is_web_origin(const std::string& v) {
  const size_t scheme = v.rfind("http://", 0) == 0 ? 7 : v.rfind("https://", 0) == 0 ? 8 : 0;
  if (scheme == 0 || v.size() == scheme || v.size() > 255) return false;
  for (size_t i = scheme; i < v.size(); ++i) {
    const char ch = v[i];
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == ':' || ch == '[' ||
          ch == ']'))
      return false;
  }
  return true;
}

// "--max-grid-voxels" -> "SOIQ_MAX_GRID_VOXELS".
std::string env_of(const char* flag) {
  std::string env = std::string("SOIQ_") + (flag + 2);
  for (char& ch : env) ch = ch == '-' ? '_' : char(std::toupper(static_cast<unsigned char>(ch)));
  return env;
}

using Setter = std::function<Status(const std::string& value, const std::string& what)>;

std::string usage_text() {
  std::string out =
      "usage: soiqd [OPTION]...\n\n"
      "Serves the soiq gRPC API (soiq.v1) and the standard health service; soiq(1) is its client.\n"
      "Every option may also be given as --option=value, or in its environment variable (the option\n"
      "wins). SIGTERM or SIGINT stops it after the calls in progress (up to 10 s).\n\n"
      "Options:\n";
  for (const OptionText& o : kOptionTexts) {
    const std::string env = env_of(o.flag);
    out += "  " + std::string(o.flag) + " " + o.value + "\n      " + o.meaning + "\n      default: " + o.default_text +
           "; environment: " + env + "\n";
  }
  out +=
      "  -h, --help\n      print this help\n\n"
      "Exit codes: 0 stopped by a signal, 2 a bad option or value (one line on stderr), 1 any other\n"
      "failure to start (the port in use, an unreadable store, certificate or token).\n";
  return out;
}

}  // namespace

const char* server_usage() {
  static const std::string text = usage_text();
  return text.c_str();
}

std::vector<std::string> server_option_flags() {
  std::vector<std::string> flags;
  for (const OptionText& o : kOptionTexts) flags.emplace_back(o.flag);
  return flags;
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
  auto on_off = [](bool& field) {
    return [&field](const std::string& v, const std::string& what) -> Status {
      if (v != "on" && v != "off") return invalid_argument(what + " must be on or off, got '" + v + "'");
      field = v == "on";
      return ok_status();
    };
  };
  // Where each option's value goes, by its flag in kOptionTexts.
  const std::map<std::string_view, Setter> setters = {
      {"--listen", text(c.listen)},
      {"--db", text(c.db_path)},
      {"--db-connections", count(c.db_connections, 1, 1000)},
      {"--replica-id", text(c.replica_id)},
      {"--replica-timeout-ms", count(c.replica_live_ms, 100, 3'600'000)},
      {"--port-file", text(c.port_file)},
      {"--max-upload-bytes", count(c.max_upload_bytes, 1, int64_t(1) << 40)},
      {"--max-grid-voxels", count(c.max_grid_voxels, 1, int64_t(1) << 40)},
      {"--memory-budget",
       [&c](const std::string& v, const std::string& what) -> Status {
         SOIQ_ASSIGN_OR_RETURN(c.memory_budget_bytes, parse_byte_size(v, what));
         return ok_status();
       }},
      {"--workers", count(c.workers, 1, 1024)},
      {"--query-result-cap", count(c.query_result_cap, 1, 10'000'000)},
      {"--stage1-cap", count(c.stage1_cap, 1, 100'000'000)},
      {"--tls-cert", text(c.tls_cert)},
      {"--tls-key", text(c.tls_key)},
      {"--token-file", text(c.token_file)},
      {"--pacs", text(c.pacs)},
      {"--pacs-calling-ae", text(c.pacs_calling_ae)},
      {"--pacs-timeout", count(c.pacs_timeout_seconds, 1, 3600)},
      {"--precompute",
       [&c](const std::string& v, const std::string& what) -> Status {
         if (v != "on" && v != "weighted" && v != "off")
           return invalid_argument(what + " must be on, weighted or off, got '" + v + "'");
         c.precompute = v != "off";
         c.precompute_weighted = v == "weighted";
         return ok_status();
       }},
      {"--http", text(c.http_listen)},
      {"--http-port-file", text(c.http_port_file)},
      {"--http-timeout", count(c.http_timeout_seconds, 1, 3600)},
      {"--http-max-connections", count(c.http_max_connections, 1, 100'000)},
      {"--keep-patient-names", on_off(c.keep_patient_names)},
      {"--keep-instances", on_off(c.keep_instances)},
      {"--http-cors-origin",
       [&c](const std::string& v, const std::string& what) -> Status {
         if (v != "*" && !is_web_origin(v))
           return invalid_argument(what +
                                   " must be an origin such as http://127.0.0.1:3000 (scheme, host and "
                                   "port, no path) or *, got '" +
                                   v + "'");
         c.http_cors_origin = v;
         return ok_status();
       }},
      {"--viewer-url",
       [&c](const std::string& v, const std::string& what) -> Status {
         const bool web = v.rfind("http://", 0) == 0 || v.rfind("https://", 0) == 0;
         if (!web || v.find("{study}") == std::string::npos || !check_text(v, 2048).ok())
           return invalid_argument(what + " must be an http:// or https:// URL with {study} in it, got '" + v + "'");
         c.viewer_url = v;
         return ok_status();
       }},
  };
  auto setter = [&](const char* flag) -> const Setter& { return setters.at(flag); };
  for (const OptionText& o : kOptionTexts) {
    const std::string env = env_of(o.flag);
    if (const char* v = getenv(env.c_str())) SOIQ_RETURN_IF_ERROR(setter(o.flag)(v, "environment variable " + env));
  }
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      return c;
    }
    const OptionText* match = nullptr;
    std::string value;
    for (const OptionText& o : kOptionTexts) {
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
    if (!match) {
      return invalid_argument("unknown option '" + arg + "'" +
                              did_you_mean(arg.substr(0, arg.find('=')), server_option_flags()));
    }
    SOIQ_RETURN_IF_ERROR(setter(match->flag)(value, match->flag));
  }
  if (!c.http_port_file.empty() && c.http_listen.empty())
    return invalid_argument("--http-port-file needs --http (where to serve DICOMweb)");
  if (c.tls_cert.empty() != c.tls_key.empty())
    return invalid_argument("--tls-cert and --tls-key go together: give both or neither");
  if (!c.pacs.empty()) {
    Result<dicom::PacsPeer> peer = parse_pacs_address(c.pacs, c.pacs_calling_ae, c.pacs_timeout_seconds);
    if (!peer.ok()) return invalid_argument("--pacs: " + peer.status().message());
    c.pacs_peer = *peer;
  }
  if (c.memory_budget_bytes == 0) c.memory_budget_bytes = default_memory_budget_bytes();
  if (c.workers == 0) c.workers = std::max(1u, std::thread::hardware_concurrency());
  if (c.replica_id.size() > 64) return invalid_argument("--replica-id must be at most 64 bytes");
  for (const char ch : c.replica_id) {
    if (static_cast<unsigned char>(ch) < 0x21 || ch == 0x7f)
      return invalid_argument("--replica-id must not contain spaces or control characters");
  }
  return c;
}

}  // namespace soiq::server
