// soiqd: the soiq server. Opens (or creates) its store (a SQLite file, or a PostgreSQL database
// shared with other replicas: --db), serves soiq.v1.Soiq with the standard health service and
// reflection, and shuts down gracefully on SIGTERM or SIGINT: it stops accepting calls, gives calls
// in flight a few seconds to finish (queries are cancelled after that), then closes the store (a
// SQLite WAL checkpoint).

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server.h>
#include <grpcpp/server_builder.h>
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "server/api/grpc_log.h"
#include "server/api/soiq_service.h"
#include "server/app/server_config.h"
#include "server/app/shared_stage2.h"
#include "server/app/store_location.h"
#include "server/http/dicomweb_server.h"
#include "server/util/listen_check.h"
#include "server/util/log.h"
#include "server/util/malloc_tuning.h"

namespace {

using soiq::Result;
using soiq::Status;

Result<std::string> read_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return soiq::invalid_argument(std::string("cannot read the ") + what + " file '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Result<std::string> read_token(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(std::string token, read_file(path, "token"));
  while (!token.empty() && (token.back() == '\n' || token.back() == '\r' || token.back() == ' ')) token.pop_back();
  if (token.size() < 16)
    return soiq::invalid_argument("the token in '" + path + "' is shorter than 16 characters; use a random one");
  return token;
}

Result<std::shared_ptr<grpc::ServerCredentials>> credentials(const soiq::server::ServerConfig& c) {
  if (c.tls_cert.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions options;
  SOIQ_ASSIGN_OR_RETURN(std::string cert, read_file(c.tls_cert, "TLS certificate"));
  SOIQ_ASSIGN_OR_RETURN(std::string key, read_file(c.tls_key, "TLS key"));
  options.pem_key_cert_pairs.push_back({key, cert});
  return grpc::SslServerCredentials(options);
}

Status write_port_file(const std::string& path, int port) {
  // Written whole, then renamed: a reader polling for the file never sees half of it.
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << port << "\n";
    if (!out) return soiq::internal_error("cannot write the port file '" + path + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) return soiq::internal_error("cannot write the port file '" + path + "': " + ec.message());
  return soiq::ok_status();
}

int fail(const Status& s) {
  std::fprintf(stderr, "soiqd: %s\n", s.to_string().c_str());
  return s.code() == soiq::StatusCode::kInvalidArgument ? 2 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  soiq::server::keep_freed_blocks_for_reuse();
  bool help = false;
  Result<soiq::server::ServerConfig> config = soiq::server::parse_server_config(argc, argv, help, std::getenv);
  if (!config.ok()) {
    std::fprintf(stderr, "soiqd: %s (soiqd --help lists the options)\n", config.status().message().c_str());
    return 2;
  }
  if (help) {
    std::fputs(soiq::server::server_usage(), stdout);
    return 0;
  }
  soiq::server::ServerConfig& c = *config;
  soiq::server::route_grpc_log();

  // Signals are taken by a dedicated thread (sigwait), so block them before any thread starts.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  Result<soiq::server::StoreLocation> where = soiq::server::parse_store_location(c.db_path);
  if (!where.ok()) return fail(where.status());
  soiq::server::StoreOpenOptions store_options;
  store_options.read_connections = std::max(2, c.workers + 2);
  // Stage-2 workers, the precompute worker and the calls being served each hold one at a time.
  store_options.connections = c.db_connections > 0 ? c.db_connections : c.workers + 4;
  Result<std::unique_ptr<soiq::db::Store>> store = soiq::server::open_store(*where, store_options);
  if (!store.ok()) return fail(store.status());
  // Replicas share stage 2 on a shared database; a SQLite file has this soiqd alone.
  c.share_stage2 = where->kind == soiq::server::StoreLocation::Kind::kPostgres;
  if (c.replica_id.empty()) c.replica_id = soiq::server::default_replica_id();
  std::string token;
  if (!c.token_file.empty()) {
    Result<std::string> t = read_token(c.token_file);
    if (!t.ok()) return fail(t.status());
    token = *t;
  }
  Result<std::shared_ptr<grpc::ServerCredentials>> creds = credentials(c);
  if (!creds.ok()) return fail(creds.status());

  // Destroyed before the store (below): its background threads (precompute, the replicas' heartbeat
  // and claims) use the store until they are joined.
  auto service = std::make_unique<soiq::server::SoiqService>(**store, c, token);
  if (const Status s = service->start_background_work(); !s.ok()) return fail(s);
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(c.listen, *creds, &port);
  // gRPC sets SO_REUSEPORT on Linux by default: a second soiqd on the same port would then start
  // without a word and share the calls with the first, each answering from its own store.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.RegisterService(service.get());
  builder.SetMaxReceiveMessageSize(8 << 20);
  std::unique_ptr<grpc::Server> server;
  {
    // A port that cannot be bound is reported below in soiqd's words, not in gRPC's.
    soiq::server::GrpcLogSilenced quiet;
    server = builder.BuildAndStart();
  }
  if (!server || port == 0) {
    const std::string why = soiq::server::why_cannot_listen(c.listen);
    return fail(soiq::Status(soiq::StatusCode::kUnavailable, why.empty() ? "cannot listen on " + c.listen : why));
  }
  // DICOMweb beside gRPC, on the same engines; stopped before the service that owns them.
  std::unique_ptr<soiq::server::http::DicomwebServer> http;
  if (!c.http_listen.empty()) {
    http = std::make_unique<soiq::server::http::DicomwebServer>(service->engines(), token);
    if (const Status s = http->start(c.http_listen); !s.ok()) {
      server->Shutdown();
      return fail(s);
    }
    if (!c.http_port_file.empty()) {
      if (const Status s = write_port_file(c.http_port_file, http->port()); !s.ok()) return fail(s);
    }
  }
  if (!c.port_file.empty()) {
    const Status s = write_port_file(c.port_file, port);
    if (!s.ok()) return fail(s);
  }
  soiq::server::log_event("info", {{"event", "listening"},
                                   {"address", c.listen},
                                   {"port", std::to_string(port)},
                                   {"db", soiq::server::redacted_store_location(c.db_path)},
                                   {"tls", c.tls_cert.empty() ? "off" : "on"},
                                   {"auth", token.empty() ? "off" : "bearer"},
                                   {"workers", std::to_string(c.workers)},
                                   {"replica", c.share_stage2 ? c.replica_id : "alone"},
                                   {"http", http ? std::to_string(http->port()) : "off"},
                                   {"patient_names", c.keep_patient_names ? "kept" : "dropped"}});

  std::thread waiter([&] {
    int sig = 0;
    sigwait(&signals, &sig);
    soiq::server::log_event("info", {{"event", "shutdown"}, {"signal", sig == SIGTERM ? "SIGTERM" : "SIGINT"}});
    server->GetHealthCheckService()->Shutdown();
    if (http) http->stop();  // lets its requests in progress finish
    // Calls in flight get 10 s; after that they are cancelled (queries notice and stop).
    server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(10));
  });
  server->Wait();
  waiter.join();
  if (http) http->stop();
  http.reset();
  server.reset();
  service.reset();
  store->reset();  // closes the database (SQLite: a WAL checkpoint)
  soiq::server::log_event("info", {{"event", "stopped"}});
  return 0;
}
