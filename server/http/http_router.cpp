#include "server/http/http_router.h"

namespace soiq::server::http {
namespace {

std::vector<std::string> split(const std::string& path) {
  std::vector<std::string> out;
  size_t from = 1;  // paths start with '/'
  while (from <= path.size()) {
    size_t slash = path.find('/', from);
    if (slash == std::string::npos) slash = path.size();
    out.push_back(path.substr(from, slash - from));
    from = slash + 1;
  }
  return out;
}

}  // namespace

void Router::add(std::string method, const std::string& pattern, Route::Handler handle, int64_t max_body_bytes,
                 std::string body_limit_name) {
  routes_.push_back(
      Route{std::move(method), split(pattern), max_body_bytes, std::move(body_limit_name), false, std::move(handle)});
}

void Router::add_open(const std::string& pattern, Route::Handler handle) {
  routes_.push_back(Route{"GET", split(pattern), 0, "", true, std::move(handle)});
}

const Route* Router::find(const std::string& method, const std::string& path, std::vector<std::string>& matches) const {
  if (path.empty() || path.front() != '/') return nullptr;
  const std::vector<std::string> segments = split(path);
  const std::string& wanted = method == "HEAD" ? std::string("GET") : method;
  for (const Route& r : routes_) {
    if (r.method != wanted || r.segments.size() != segments.size()) continue;
    std::vector<std::string> captured = {path};
    bool match = true;
    for (size_t i = 0; i < segments.size() && match; ++i) {
      if (r.segments[i] == "{}") {
        match = !segments[i].empty();
        captured.push_back(segments[i]);
      } else {
        match = r.segments[i] == segments[i];
      }
    }
    if (match) {
      matches = std::move(captured);
      return &r;
    }
  }
  return nullptr;
}

}  // namespace soiq::server::http
