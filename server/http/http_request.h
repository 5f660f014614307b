#pragma once
// A request as soiqd's HTTP handlers see it: method, decoded path and query, headers, the route's
// captured path segments, the received body (a file, for the routes that take one) and a way to
// ask whether the client is still there. Built by http_connection.cpp from what the bounded parser
// read (http_request_parser.h); the handlers never touch the socket.

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/status.h"

namespace soiq::server::http {

using QueryParams = std::vector<std::pair<std::string, std::string>>;

struct HttpRequest {
  std::string method;  // as sent: "GET", "POST", ...
  std::string target;  // as sent: path and query, still percent-encoded
  std::string path;    // percent-decoded
  QueryParams params;  // the query's name=value pairs in order, percent- and '+'-decoded
  std::vector<std::pair<std::string, std::string>> headers;  // in order, names as sent
  std::vector<std::string> matches;                          // matches[1..]: the path segments the route captured
  std::string body_path;                                     // the received body ("" for routes that take none)
  int64_t body_bytes = 0;
  // True once the client has closed its side of the connection: a long answer stops early.
  std::function<bool()> client_gone = [] { return false; };
  // For answers sent as they are computed (chunked transfer coding): start_chunks sends the head,
  // 200 with this content type; send_chunk sends one piece. Each returns once its bytes are
  // written, so a slow reader slows the handler and nothing queues up in memory; CANCELLED once the
  // client has gone, DEADLINE_EXCEEDED when a write stalls past --http-timeout. A handler that
  // started returns HttpReply::chunked (the connection ends the answer); one that fails after
  // starting has the connection cut short, since its status line has already gone.
  std::function<Status(const std::string& content_type)> start_chunks;
  std::function<Status(std::string piece)> send_chunk;

  bool has_header(std::string_view name) const;
  // The first header of that name (case-insensitive), or "".
  std::string header(std::string_view name) const;
};

// Splits a request target ("/a%20b/c?x=1&y=%2F") into its decoded path and query pairs.
// INVALID_ARGUMENT for a target that is not origin-form (no leading '/'), or a malformed or NUL
// percent escape. Segments are not resolved ("/a/../b" stays as it is): soiqd's paths name records,
// never files.
Status parse_target(const std::string& target, std::string& path, QueryParams& params);

}  // namespace soiq::server::http
