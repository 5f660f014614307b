#include "server/http/dicomweb_server.h"

#include <httplib.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <openssl/crypto.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "server/http/http_handlers.h"
#include "server/http/http_status.h"
#include "server/util/log.h"

namespace soiq::server::http {
namespace {

constexpr char kUid[] = "([^/]+)";  // a path segment: a UID, or any id soiq was given

struct Address {
  std::string host;
  int port = 0;
};

Result<Address> parse_listen(const std::string& listen) {
  const size_t colon = listen.rfind(':');
  if (colon == std::string::npos || colon == 0) return invalid_argument("--http '" + listen + "' is not HOST:PORT");
  Address a;
  a.host = listen.substr(0, colon);
  if (a.host.size() > 2 && a.host.front() == '[' && a.host.back() == ']') a.host = a.host.substr(1, a.host.size() - 2);
  const std::string port = listen.substr(colon + 1);
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
      std::stoi(port) > 65535)
    return invalid_argument("--http '" + listen + "': the port must be 0..65535");
  a.port = std::stoi(port);
  return a;
}

// The Host header when it is a plain host[:port] (it goes into RetrieveURLs), else the address
// soiqd listens on.
std::string url_host(const httplib::Request& req, const std::string& fallback) {
  const std::string host = req.get_header_value("Host");
  if (host.empty() || host.size() > 255) return fallback;
  for (const char c : host) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == ':' || c == '[' || c == ']'))
      return fallback;
  }
  return host;
}

void write_reply(httplib::Response& res, const Result<HttpReply>& r) {
  if (!r.ok()) {
    res.status = http_status_of(r.status().code());
    res.set_content(error_body(r.status()), "application/json");
    return;
  }
  res.status = r->status;
  for (const auto& [k, v] : r->headers) res.set_header(k.c_str(), v);
  if (r->status == 406 && r->body.empty()) {
    res.set_content(error_body(invalid_argument("not acceptable: this resource is answered as " +
                                                (r->content_type.empty() ? "JSON" : r->content_type)),
                               406),
                    "application/json");
    return;
  }
  res.set_content(r->body, r->content_type.empty() ? "application/json" : r->content_type.c_str());
}

}  // namespace

bool accepts(const httplib::Request& req, const std::string& type) {
  if (!req.has_header("Accept")) return true;
  const std::string accept = req.get_header_value("Accept");
  const std::string major = type.substr(0, type.find('/'));
  size_t from = 0;
  while (from <= accept.size()) {
    size_t comma = accept.find(',', from);
    if (comma == std::string::npos) comma = accept.size();
    std::string item = accept.substr(from, comma - from);
    item = item.substr(0, item.find(';'));
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (item == "*/*" || item == type || item == major + "/*") return true;
    from = comma + 1;
  }
  return false;
}

struct DicomwebServer::Impl {
  Impl(AppEngines e, std::string t) : engines(std::move(e)), token(std::move(t)) {}

  AppEngines engines;
  std::string token;
  std::unique_ptr<httplib::Server> server;
  std::thread thread;
  int port = 0;
  std::string scheme;
  std::string listen_host;

  bool authorized(const httplib::Request& req) const {
    if (token.empty()) return true;
    const std::string given = req.get_header_value("Authorization");
    const std::string expected = "Bearer " + token;
    // Constant time: a wrong token must not leak how much of it was right.
    return given.size() == expected.size() && CRYPTO_memcmp(given.data(), expected.data(), given.size()) == 0;
  }

  HandlerContext context(const httplib::Request& req) const {
    return {engines, scheme + "://" + url_host(req, listen_host + ":" + std::to_string(port)) + "/dicom-web"};
  }

  template <typename Fn>
  httplib::Server::Handler handler(Fn fn) {
    return [this, fn](const httplib::Request& req, httplib::Response& res) { write_reply(res, fn(context(req), req)); };
  }

  void add_routes() {
    httplib::Server& s = *server;
    const std::string uid = kUid;
    auto qido_at = [this](QidoLevel level, int study_group, int series_group) {
      return handler([level, study_group, series_group](const HandlerContext& c, const httplib::Request& req) {
        const std::string study = study_group > 0 ? std::string(req.matches[study_group]) : "";
        const std::string series = series_group > 0 ? std::string(req.matches[series_group]) : "";
        return qido(c, level, study, series, req);
      });
    };
    s.Get("/dicom-web/studies", qido_at(QidoLevel::kStudy, 0, 0));
    s.Get("/dicom-web/series", qido_at(QidoLevel::kSeries, 0, 0));
    s.Get("/dicom-web/instances", qido_at(QidoLevel::kInstance, 0, 0));
    s.Get("/dicom-web/studies/" + uid + "/series", qido_at(QidoLevel::kSeries, 1, 0));
    s.Get("/dicom-web/studies/" + uid + "/instances", qido_at(QidoLevel::kInstance, 1, 0));
    s.Get("/dicom-web/studies/" + uid + "/series/" + uid + "/instances", qido_at(QidoLevel::kInstance, 1, 2));
    auto wado_at = [this](WadoWhat what, int depth) {
      return handler([what, depth](const HandlerContext& c, const httplib::Request& req) {
        const auto group = [&](int g) { return depth >= g ? std::string(req.matches[g]) : std::string(); };
        return wado(c, what, group(1), group(2), group(3), req);
      });
    };
    const std::string study = "/dicom-web/studies/" + uid;
    const std::string series = study + "/series/" + uid;
    const std::string instance = series + "/instances/" + uid;
    s.Get(study, wado_at(WadoWhat::kInstances, 1));
    s.Get(series, wado_at(WadoWhat::kInstances, 2));
    s.Get(instance, wado_at(WadoWhat::kInstances, 3));
    s.Get(study + "/metadata", wado_at(WadoWhat::kMetadata, 1));
    s.Get(series + "/metadata", wado_at(WadoWhat::kMetadata, 2));
    s.Get(instance + "/metadata", wado_at(WadoWhat::kMetadata, 3));
    s.Get(instance + "/bulkdata", wado_at(WadoWhat::kBulkData, 3));
    s.Get("/soiq/v1/query",
          handler([](const HandlerContext& c, const httplib::Request& req) { return soiq_query(c, req); }));
    // STOW-RS reads its body itself, to disk (stow_handler.cpp).
    auto stow_at = [this](bool study_in_path) {
      return [this, study_in_path](const httplib::Request& req, httplib::Response& res,
                                   const httplib::ContentReader& reader) {
        write_reply(res, stow(context(req), study_in_path ? std::string(req.matches[1]) : "", req, reader));
      };
    };
    s.Post("/dicom-web/studies", stow_at(false));
    s.Post(study, stow_at(true));
  }
};

DicomwebServer::DicomwebServer(AppEngines engines, std::string token)
    : impl_(std::make_unique<Impl>(std::move(engines), std::move(token))) {}

DicomwebServer::~DicomwebServer() { stop(); }

Status DicomwebServer::start(const std::string& listen) {
  SOIQ_ASSIGN_OR_RETURN(const Address address, parse_listen(listen));
  const ServerConfig& config = impl_->engines.config;
  if (!config.tls_cert.empty()) {
    for (const std::string& f : {config.tls_cert, config.tls_key}) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(f, ec)) return invalid_argument("cannot read the TLS file '" + f + "'");
    }
    impl_->server = std::make_unique<httplib::SSLServer>(config.tls_cert.c_str(), config.tls_key.c_str());
    impl_->scheme = "https";
  } else {
    impl_->server = std::make_unique<httplib::Server>();
    impl_->scheme = "http";
  }
  httplib::Server& s = *impl_->server;
  if (!s.is_valid()) return invalid_argument("the TLS certificate or key could not be loaded for --http");
  const int threads = std::max(4, config.workers + 2);
  s.new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
  // One byte more than the limit: a chunked STOW body passing it reaches stow_handler.cpp's own
  // check, which says which limit; a Content-Length past it is refused before anything is read.
  s.set_payload_max_length(size_t(config.max_upload_bytes) + 1);
  // httplib sets SO_REUSEPORT by default: a second soiqd on the same port would then start without a
  // word and share the requests, each answering from its own store (as gRPC would; main.cpp).
  // TCP_NODELAY too (accepted sockets inherit it): httplib writes a reply's headers and body
  // apart, and with Nagle's algorithm the body of a small reply on a kept-alive connection waits
  // for the client's delayed ACK, 40 ms a request.
  s.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    setsockopt(sock, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  });
  s.set_read_timeout(30, 0);
  s.set_write_timeout(60, 0);
  Impl* impl = impl_.get();
  s.set_pre_routing_handler([impl](const httplib::Request& req, httplib::Response& res) {
    if (impl->authorized(req)) return httplib::Server::HandlerResponse::Unhandled;
    res.status = 401;
    res.set_header("WWW-Authenticate", "Bearer");
    const bool given = req.has_header("Authorization");
    res.set_content(
        error_body(Status(StatusCode::kUnauthenticated, given ? "the bearer token is not valid for this server"
                                                              : "this server needs 'Authorization: Bearer TOKEN'")),
        "application/json");
    return httplib::Server::HandlerResponse::Handled;
  });
  s.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    Status why = not_found("no such resource: " + req.method + " " + req.path);
    if (res.status == 413)
      why = resource_exhausted("the request body is larger than this server accepts (--max-upload-bytes)");
    else if (res.status == 400)
      why = invalid_argument("the request is malformed");
    else if (res.status != 404)
      why = Status(StatusCode::kUnknown, "HTTP " + std::to_string(res.status));
    res.set_content(error_body(why), "application/json");
  });
  s.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    std::string what = "an unexpected error";
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    res.status = 500;
    res.set_content(error_body(internal_error(what)), "application/json");
  });
  s.set_logger([](const httplib::Request& req, const httplib::Response& res) {
    log_event("info",
              {{"event", "http"}, {"method", req.method}, {"path", req.path}, {"status", std::to_string(res.status)}});
  });
  impl_->add_routes();
  impl_->listen_host = address.host.find(':') != std::string::npos ? "[" + address.host + "]" : address.host;
  if (address.port == 0) {
    impl_->port = s.bind_to_any_port(address.host);
    if (impl_->port <= 0) return Status(StatusCode::kUnavailable, "cannot listen for DICOMweb on " + listen);
  } else {
    if (!s.bind_to_port(address.host, address.port))
      return Status(StatusCode::kUnavailable,
                    "cannot listen for DICOMweb on " + listen + " (in use, or not an address here)");
    impl_->port = address.port;
  }
  impl_->thread = std::thread([impl] { impl->server->listen_after_bind(); });
  return ok_status();
}

int DicomwebServer::port() const { return impl_->port; }

void DicomwebServer::stop() {
  if (impl_->server) impl_->server->stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace soiq::server::http
