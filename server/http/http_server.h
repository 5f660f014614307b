#pragma once
// soiqd's HTTP/1.1 server, on Boost.Beast and Asio: bounded by http_limits.h from the first byte,
// authenticated by a bearer token, routed by http_router.h, with plain TCP or TLS (OpenSSL).
//
// Threads: one Asio thread owns every socket: it reads heads and bodies, waits on slow clients
// and writes answers, so a slow or stalled client costs a connection (a socket and at most a
// head's bytes), never a thread. Handlers run on a pool of their own (`handler_threads`), one
// request at a time per connection; a handler may block (the store, the worker pool).
//
// Per request, in order: the head is read within --http-timeout and the limits; the token is
// checked (401 with WWW-Authenticate: Bearer); the route is found (404); a body is accepted only
// by a route that takes one, up to its limit (413, before reading when Content-Length says so;
// "Expect: 100-continue" is answered); the handler runs; one byte range may be served (http_range.h);
// the answer is written, within --http-timeout of progress. Every error carries the JSON body of
// http_status.h. Requests are logged by method, path, status, bytes and time (never the query: it
// may hold a patient's name). An answer to a request whose body was refused closes the
// connection after draining what the client was sending (so it reads the answer, not a reset).

#include <memory>
#include <string>

#include "core/base/status.h"
#include "server/http/http_limits.h"
#include "server/http/http_router.h"

namespace soiq::server::http {

struct HttpServerOptions {
  HttpLimits limits;
  std::string token;        // "": no authentication
  std::string cors_origin;  // the origin answered with CORS headers (cors.h), "*" any, "": none
  std::string tls_cert;     // PEM files of soiqd's own configuration; "": plain HTTP
  std::string tls_key;
  int handler_threads = 4;
};

class HttpServer {
 public:
  HttpServer(HttpServerOptions options, Router router);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds HOST:PORT (port 0: any free one) and serves. UNAVAILABLE when the address cannot be
  // bound; INVALID_ARGUMENT for a malformed address or an unreadable certificate or key.
  Status start(const std::string& listen);
  int port() const;
  // "http" or "https".
  const std::string& scheme() const;
  // Stops accepting, closes idle connections, lets the requests in progress finish (up to
  // --http-timeout), joins. Idempotent.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace soiq::server::http
