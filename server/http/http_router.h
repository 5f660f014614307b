#pragma once
// Routes by method and path pattern: "/dicom-web/studies/{}/series" matches a path of exactly
// those segments, each "{}" capturing one non-empty segment (request.matches[1], [2], ...). No
// regular expression runs on a client's path. A GET route answers HEAD too. Whether a route takes
// a body, and how much, is decided here, before a byte of it is read.

#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "server/http/http_reply.h"
#include "server/http/http_request.h"

namespace soiq::server::http {

struct Route {
  using Handler = std::function<Result<HttpReply>(const HttpRequest&)>;
  std::string method;
  std::vector<std::string> segments;  // the pattern split at '/', "{}" for a capture
  int64_t max_body_bytes = 0;         // 0: the route takes no body
  std::string body_limit_name;        // the option that sets it, for the 413's message
  // Answered without the bearer token: only the query page's static files, which hold nothing of
  // the store (the page asks for the token before it calls the API).
  bool open = false;
  Handler handle;
};

class Router {
 public:
  void add(std::string method, const std::string& pattern, Route::Handler handle, int64_t max_body_bytes = 0,
           std::string body_limit_name = "");
  // A GET route answered without the token (Route::open).
  void add_open(const std::string& pattern, Route::Handler handle);
  // The route for `method` and decoded `path`, its captures in `matches` ([0] is the path); nullptr
  // when none matches.
  const Route* find(const std::string& method, const std::string& path, std::vector<std::string>& matches) const;

 private:
  std::vector<Route> routes_;
};

}  // namespace soiq::server::http
