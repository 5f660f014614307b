// Feeds raw bytes to what soiqd's HTTP server does with a request before any handler runs: the
// bounded parser (http_request_parser.h), fed in two pieces split where the first byte says, as a
// socket would deliver them, with a small body limit; then, for a head it accepted, the target's
// decoding (parse_target), the router (http_router.h) and a byte range over an answer
// (http_range.h). A bug is any crash or sanitizer report, a run over -timeout, or a broken
// contract: a head kept past its limits, a body past its limit, a refusal with a status that is
// not the client's (4xx/505), a range answer that is not a slice of the answer.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/require.h"
#include "server/http/http_range.h"
#include "server/http/http_request_parser.h"
#include "server/http/http_router.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace http = soiq::server::http;
  using soiq::fuzz::require;
  if (size == 0) return 0;
  const size_t split = size_t(data[0]) * (size - 1) / 255;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);

  http::HttpLimits limits;
  limits.max_request_line = 256;
  limits.max_header_line = 128;
  limits.max_header_count = 8;
  limits.max_head_bytes = 1024;
  http::HttpRequestParser parser(limits);
  parser.eager(true);
  std::string body;
  constexpr int64_t kMaxBody = 100;
  bool body_accepted = false;
  boost::beast::error_code ec;
  size_t at = 0;
  for (const size_t end : {split, bytes.size()}) {
    // Beast reads from a buffer that keeps what it did not consume, as the connection's does.
    while (at < end && !ec && !parser.is_done()) {
      const size_t used = parser.put(boost::asio::buffer(bytes.data() + at, end - at), ec);
      at += used;  // consumed even when it asks for more; the rest is presented again
      if (ec == boost::beast::http::error::need_more) {
        ec = {};
        break;
      }
      if (!ec && parser.is_header_done() && !body_accepted) {
        body_accepted = true;
        parser.accept_body(kMaxBody, "the fuzz limit", [&](std::string_view piece) {
          body.append(piece);
          return soiq::ok_status();
        });
      }
      if (used == 0) break;
    }
  }
  require(int64_t(body.size()) <= kMaxBody && parser.body_bytes() <= kMaxBody, "a body passed its limit");
  if (ec) {
    const std::optional<http::Refusal> r = http::refusal_of(parser, ec, bytes.substr(0, at), limits);
    if (r) require((r->http_status >= 400 && r->http_status < 500) || r->http_status == 505, "a refusal is not 4xx");
    return 0;
  }
  if (!parser.is_header_done()) return 0;
  const http::HttpRequestHead& head = parser.head();
  require(head.headers.size() <= limits.max_header_count, "more headers kept than the limit");
  for (const auto& [name, value] : head.headers)
    require(name.size() + value.size() + 2 <= limits.max_header_line, "a header line kept past its limit");
  require(head.method.size() + head.target.size() + 10 <= limits.max_request_line, "a request line past its limit");

  http::HttpRequest request;
  if (!http::parse_target(head.target, request.path, request.params).ok()) return 0;
  require(request.path.find('\0') == std::string::npos, "a decoded path holds a NUL");
  http::Router router;
  router.add("GET", "/dicom-web/studies/{}/series/{}", [](const http::HttpRequest&) { return http::HttpReply{}; });
  router.add("POST", "/dicom-web/studies", [](const http::HttpRequest&) { return http::HttpReply{}; });
  std::vector<std::string> matches;
  if (const http::Route* route = router.find(head.method, request.path, matches)) {
    for (size_t i = 1; i < matches.size(); ++i)
      require(!matches[i].empty() && matches[i].find('/') == std::string::npos, "a capture is not one segment");
  }
  // A range over an answer made of the body and the target, in two pieces.
  http::HttpReply reply;
  reply.body = body;
  reply.pieces = {head.target};
  const std::string whole = reply.body + head.target;
  std::string range;
  for (const auto& [name, value] : head.headers)
    if (name == "Range") range = value;
  http::apply_range(range, 1, reply);
  if (reply.status == 206) {
    require(reply.pieces.empty() && whole.find(reply.body) != std::string::npos && !reply.body.empty(),
            "a range answer is not a slice of the answer");
  } else {
    require(reply.status == 200 || reply.status == 416, "a range gave another status");
  }
  return 0;
}
