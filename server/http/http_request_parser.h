#pragma once
// An HTTP/1.1 request parser that holds soiqd's bounds (http_limits.h) while the bytes arrive.
// Boost.Beast's basic_parser does the reading: it finds the end of a head without copying it,
// refuses a head longer than max_head_bytes before it is whole, and decodes chunked bodies; this
// class decides what is kept (the head's fields, counted and measured) and where the body goes
// (a sink the connection gives once it knows the route, bounded whatever the framing).
//
// Why Beast: the packaged cpp-httplib (0.11) read a request line or a header line into a buffer
// that grew without bound and counted no headers, so a client could grow soiqd by hundreds of MiB
// before its token was checked; libmicrohttpd answers its own limits with HTML bodies and resets
// its timeout on every byte. Beast leaves those decisions to us, with the same OpenSSL as gRPC.
//
// refusal() says why a parse stopped, as the HTTP status and error a client gets: 414 (request
// line), 431 (a header line, too many headers, the head as a whole), 413 (the body), 400 (not
// HTTP). refusal_of() turns any parse error the reading reported into one.

#include <boost/beast/http/basic_parser.hpp>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/status.h"
#include "server/http/http_limits.h"

namespace soiq::server::http {

struct Refusal {
  int http_status = 400;
  Status why;
};

struct HttpRequestHead {
  std::string method;
  std::string target;
  unsigned version = 11;  // 10 for HTTP/1.0
  std::vector<std::pair<std::string, std::string>> headers;
};

class HttpRequestParser : public boost::beast::http::basic_parser<true> {
 public:
  using Sink = std::function<Status(std::string_view)>;

  explicit HttpRequestParser(const HttpLimits& limits);

  // After the head: at most `max_bytes` of body, each piece given to `sink` (nullptr: none kept).
  // `what` names the limit in the refusal ("--max-upload-bytes").
  void accept_body(int64_t max_bytes, std::string what, Sink sink);

  const HttpRequestHead& head() const { return head_; }
  int64_t body_bytes() const { return body_bytes_; }
  const std::optional<Refusal>& refusal() const { return refusal_; }
  // Why a body past accept_body's limit is refused, in words that name the limit.
  Status body_refusal() const;

 private:
  void on_request_impl(boost::beast::http::verb, boost::beast::string_view method, boost::beast::string_view target,
                       int version, boost::beast::error_code& ec) override;
  void on_response_impl(int, boost::beast::string_view, int, boost::beast::error_code& ec) override;
  void on_field_impl(boost::beast::http::field, boost::beast::string_view name, boost::beast::string_view value,
                     boost::beast::error_code& ec) override;
  void on_header_impl(boost::beast::error_code&) override {}
  void on_body_init_impl(const boost::optional<std::uint64_t>& content_length, boost::beast::error_code& ec) override;
  std::size_t on_body_impl(boost::beast::string_view body, boost::beast::error_code& ec) override;
  void on_chunk_header_impl(std::uint64_t size, boost::beast::string_view, boost::beast::error_code& ec) override;
  std::size_t on_chunk_body_impl(std::uint64_t, boost::beast::string_view body, boost::beast::error_code& ec) override;
  void on_finish_impl(boost::beast::error_code&) override {}

  void refuse(int http_status, Status why, boost::beast::error_code& ec);
  std::size_t take(boost::beast::string_view piece, boost::beast::error_code& ec);

  HttpLimits limits_;
  HttpRequestHead head_;
  size_t fields_ = 0;
  int64_t max_body_bytes_ = 0;
  std::string body_limit_name_;
  Sink sink_;
  int64_t body_bytes_ = 0;
  std::optional<Refusal> refusal_;
};

// Why reading a request failed with `ec`: the parser's own refusal when it made one, else the
// status for Beast's error (header_limit or a full buffer: 414 when `buffered` holds no line end
// within max_request_line, else 431; body_limit: 413; any other parse error: 400).
// nullopt for errors that are not the client's request (end of stream, timeout, reset).
std::optional<Refusal> refusal_of(const HttpRequestParser& parser, const boost::beast::error_code& ec,
                                  std::string_view buffered, const HttpLimits& limits);

}  // namespace soiq::server::http
