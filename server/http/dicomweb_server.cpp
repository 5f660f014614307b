#include "server/http/dicomweb_server.h"

#include "server/http/http_handlers.h"
#include "server/http/http_server.h"
#include "server/http/multipart.h"
#include "server/http/web_files.h"

namespace soiq::server::http {
namespace {

// The Host header when it is a plain host[:port] (it goes into RetrieveURLs), else the address
// soiqd listens on.
std::string url_host(const HttpRequest& req, const std::string& fallback) {
  const std::string host = req.header("Host");
  if (host.empty() || host.size() > 255) return fallback;
  for (const char c : host) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == ':' || c == '[' || c == ']'))
      return fallback;
  }
  return host;
}

}  // namespace

std::vector<AcceptItem> accept_items(const HttpRequest& req) {
  std::vector<AcceptItem> items;
  if (!req.has_header("Accept")) return items;
  const std::string accept = req.header("Accept");
  size_t from = 0;
  while (from <= accept.size()) {
    size_t comma = accept.find(',', from);
    if (comma == std::string::npos) comma = accept.size();
    const std::string item = accept.substr(from, comma - from);
    from = comma + 1;
    std::string media = item.substr(0, item.find(';'));
    media.erase(0, media.find_first_not_of(' '));
    media.erase(media.find_last_not_of(' ') + 1);
    for (char& ch : media) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (media.empty()) continue;
    items.push_back({media, header_parameter(item, "type"), header_parameter(item, "transfer-syntax")});
  }
  return items;
}

std::vector<std::string> accepted_types(const HttpRequest& req) {
  std::vector<std::string> types;
  for (AcceptItem& item : accept_items(req)) types.push_back(std::move(item.media));
  return types;
}

bool accepts(const HttpRequest& req, const std::string& type) {
  if (!req.has_header("Accept")) return true;
  const std::string major = type.substr(0, type.find('/'));
  for (const std::string& item : accepted_types(req))
    if (item == "*/*" || item == type || item == major + "/*") return true;
  return false;
}

std::function<Status()> stop_when_client_gone(const HttpRequest& req) {
  return [&req]() -> Status {
    return req.client_gone() ? Status(StatusCode::kCancelled, "the HTTP client closed its connection") : ok_status();
  };
}

Result<QueryAnswer> run_query(const AppEngines& engines, const Query& query, const HttpRequest& req) {
  QueryAnswer answer;
  QueryOutput out;
  out.progress = [](const QueryProgress&) { return ok_status(); };
  out.row = [&](QueryRow&& r) {
    answer.rows.push_back(std::move(r));
    return ok_status();
  };
  SOIQ_ASSIGN_OR_RETURN(answer.summary, engines.queries.run(query, stop_when_client_gone(req), out));
  return answer;
}

struct DicomwebServer::Impl {
  Impl(AppEngines e, std::string t) : engines(std::move(e)), token(std::move(t)) {}

  AppEngines engines;
  std::string token;
  std::unique_ptr<HttpServer> server;
  std::string listen_host;

  HandlerContext context(const HttpRequest& req) const {
    return {engines, server->scheme() + "://" + url_host(req, listen_host + ":" + std::to_string(server->port())) +
                         "/dicom-web"};
  }

  template <typename Fn>
  Route::Handler handler(Fn fn) {
    return [this, fn](const HttpRequest& req) { return fn(context(req), req); };
  }

  Router routes() {
    Router r;
    auto qido_at = [this](QidoLevel level) {
      return handler([level](const HandlerContext& c, const HttpRequest& req) {
        const auto group = [&](size_t g) { return g < req.matches.size() ? req.matches[g] : std::string(); };
        return qido(c, level, group(1), group(2), req);
      });
    };
    r.add("GET", "/dicom-web/studies", qido_at(QidoLevel::kStudy));
    r.add("GET", "/dicom-web/series", qido_at(QidoLevel::kSeries));
    r.add("GET", "/dicom-web/instances", qido_at(QidoLevel::kInstance));
    r.add("GET", "/dicom-web/studies/{}/series", qido_at(QidoLevel::kSeries));
    r.add("GET", "/dicom-web/studies/{}/instances", qido_at(QidoLevel::kInstance));
    r.add("GET", "/dicom-web/studies/{}/series/{}/instances", qido_at(QidoLevel::kInstance));
    auto wado_at = [this](WadoWhat what) {
      return handler([what](const HandlerContext& c, const HttpRequest& req) {
        const auto group = [&](size_t g) { return g < req.matches.size() ? req.matches[g] : std::string(); };
        return wado(c, what, group(1), group(2), group(3), group(4), req);
      });
    };
    const std::string study = "/dicom-web/studies/{}";
    const std::string series = study + "/series/{}";
    const std::string instance = series + "/instances/{}";
    r.add("GET", study, wado_at(WadoWhat::kInstances));
    r.add("GET", series, wado_at(WadoWhat::kInstances));
    r.add("GET", instance, wado_at(WadoWhat::kInstances));
    r.add("GET", study + "/metadata", wado_at(WadoWhat::kMetadata));
    r.add("GET", series + "/metadata", wado_at(WadoWhat::kMetadata));
    r.add("GET", instance + "/metadata", wado_at(WadoWhat::kMetadata));
    r.add("GET", instance + "/bulkdata", wado_at(WadoWhat::kBulkData));
    r.add("GET", instance + "/frames/{}", wado_at(WadoWhat::kFrames));
    auto rendered_at = [this](bool thumbnail) {
      return handler([thumbnail](const HandlerContext& c, const HttpRequest& req) {
        const auto group = [&](size_t g) { return g < req.matches.size() ? req.matches[g] : std::string(); };
        return wado_rendered(c, thumbnail, group(1), group(2), group(3), group(4), req);
      });
    };
    r.add("GET", study + "/thumbnail", rendered_at(true));
    for (const std::string& at : {series, instance, instance + "/frames/{}"}) {
      r.add("GET", at + "/rendered", rendered_at(false));
      r.add("GET", at + "/thumbnail", rendered_at(true));
    }
    r.add("GET", "/soiq/v1/query",
          handler([](const HandlerContext& c, const HttpRequest& req) { return soiq_query(c, req); }));
    // The query page: the files built into soiqd (web/), the only answers without the token.
    const auto page_file = [](const std::string& path) -> Result<HttpReply> {
      const WebFile* f = find_web_file(path);
      if (f == nullptr) return not_found("no such file of the query page: " + path);
      HttpReply reply{200, std::string(f->media_type), std::string(f->bytes), {}};
      reply.headers.emplace("Cache-Control", "no-cache");
      reply.headers.emplace("X-Content-Type-Options", "nosniff");
      reply.headers.emplace("Content-Security-Policy",
                            "default-src 'self'; img-src 'self' blob: data:; style-src 'self'; frame-ancestors 'none'");
      return reply;
    };
    r.add_open("/", [page_file](const HttpRequest&) { return page_file("index.html"); });
    r.add_open("/ui/{}", [page_file](const HttpRequest& req) {
      return page_file(req.matches.size() > 1 ? req.matches[1] : std::string());
    });
    r.add("GET", "/soiq/v1/query/plot",
          handler([](const HandlerContext& c, const HttpRequest& req) { return soiq_query_plot(c, req); }));
    const std::pair<const char*, StructureResource> structure_resources[] = {
        {"rendered", StructureResource::kRendered},
        {"thumbnail", StructureResource::kThumbnail},
        {"seg", StructureResource::kSeg},
        {"mask", StructureResource::kMask},
        {"surface", StructureResource::kSurface}};
    for (const auto& [name, what] : structure_resources)
      r.add("GET", std::string("/soiq/v1/structures/{}/") + name,
            handler([what = what](const HandlerContext& c, const HttpRequest& req) {
              return soiq_structure(c, what, req.matches.size() > 1 ? req.matches[1] : std::string(), req);
            }));
    r.add("GET", "/soiq/v1/info",
          handler([](const HandlerContext& c, const HttpRequest& req) { return soiq_info(c, req); }));
    // STOW-RS: the only routes with a body, received to a file (http_connection.cpp).
    auto stow_at = [this] {
      return handler([](const HandlerContext& c, const HttpRequest& req) {
        return stow(c, req.matches.size() > 1 ? req.matches[1] : std::string(), req);
      });
    };
    const int64_t max_body = engines.config.max_upload_bytes;
    r.add("POST", "/dicom-web/studies", stow_at(), max_body, "--max-upload-bytes");
    r.add("POST", study, stow_at(), max_body, "--max-upload-bytes");
    return r;
  }
};

DicomwebServer::DicomwebServer(AppEngines engines, std::string token)
    : impl_(std::make_unique<Impl>(std::move(engines), std::move(token))) {}

DicomwebServer::~DicomwebServer() { stop(); }

Status DicomwebServer::start(const std::string& listen) {
  const ServerConfig& config = impl_->engines.config;
  HttpServerOptions options;
  options.token = impl_->token;
  options.cors_origin = config.http_cors_origin;
  options.tls_cert = config.tls_cert;
  options.tls_key = config.tls_key;
  options.handler_threads = std::max(4, config.workers + 2);
  options.limits.timeout_seconds = config.http_timeout_seconds;
  options.limits.max_connections = config.http_max_connections;
  impl_->server = std::make_unique<HttpServer>(std::move(options), impl_->routes());
  SOIQ_RETURN_IF_ERROR(impl_->server->start(listen));
  const std::string host = listen.substr(0, listen.rfind(':'));
  impl_->listen_host = host.find(':') != std::string::npos && host.front() != '[' ? "[" + host + "]" : host;
  return ok_status();
}

int DicomwebServer::port() const { return impl_->server ? impl_->server->port() : 0; }

void DicomwebServer::stop() {
  if (impl_->server) impl_->server->stop();
}

}  // namespace soiq::server::http
