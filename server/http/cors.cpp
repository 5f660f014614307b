#include "server/http/cors.h"

namespace soiq::server::http {
namespace {

// The origin the answer names: the request's own when it is the allowed one (or any is allowed);
// "" when the request is not cross-origin or comes from another site.
std::string answered_origin(const std::string& allowed, const HttpRequest& req) {
  if (allowed.empty() || !req.has_header("Origin")) return "";
  const std::string origin = req.header("Origin");
  if (allowed == "*") return "*";
  return origin == allowed ? origin : "";
}

}  // namespace

std::optional<HttpReply> cors_preflight(const std::string& allowed, const HttpRequest& req) {
  if (req.method != "OPTIONS" || !req.has_header("Access-Control-Request-Method")) return std::nullopt;
  const std::string origin = answered_origin(allowed, req);
  if (origin.empty()) return std::nullopt;
  HttpReply r{204, "text/plain", "", {}};
  r.headers.emplace("Access-Control-Allow-Origin", origin);
  r.headers.emplace("Access-Control-Allow-Methods", "GET, HEAD, POST, OPTIONS");
  // What DICOMweb clients send: the token, content negotiation, STOW's body type, a byte range.
  r.headers.emplace("Access-Control-Allow-Headers", "Authorization, Accept, Content-Type, Range");
  r.headers.emplace("Access-Control-Max-Age", "600");
  r.headers.emplace("Vary", "Origin");
  return r;
}

void add_cors_headers(const std::string& allowed, const HttpRequest& req,
                      std::multimap<std::string, std::string>& headers) {
  const std::string origin = answered_origin(allowed, req);
  // A preflight's answer has them already; a browser refuses an origin named twice.
  if (origin.empty() || headers.count("Access-Control-Allow-Origin") > 0) return;
  headers.emplace("Access-Control-Allow-Origin", origin);
  // Warning carries STOW's per-part problems; Content-Range a served range.
  headers.emplace("Access-Control-Expose-Headers", "Content-Type, Content-Length, Content-Range, Warning");
  headers.emplace("Vary", "Origin");
}

}  // namespace soiq::server::http
