#include "server/http/http_request_parser.h"

#include <boost/beast/http/error.hpp>
#include <limits>

namespace soiq::server::http {

namespace beast = boost::beast;
namespace bhttp = boost::beast::http;

HttpRequestParser::HttpRequestParser(const HttpLimits& limits) : limits_(limits) {
  header_limit(std::uint32_t(limits.max_head_bytes));
  // The body is bounded by accept_body's limit, counted here. Beast's own limit stays out of the
  // way (1.74 compares a length with an empty optional as if the limit were 0, so it is set, high).
  body_limit(std::numeric_limits<std::uint64_t>::max());
}

void HttpRequestParser::accept_body(int64_t max_bytes, std::string what, Sink sink) {
  max_body_bytes_ = max_bytes;
  body_limit_name_ = std::move(what);
  sink_ = std::move(sink);
}

void HttpRequestParser::refuse(int http_status, Status why, beast::error_code& ec) {
  refusal_ = Refusal{http_status, std::move(why)};
  ec = bhttp::error::bad_value;  // any error stops the parse; refusal_ says which
}

void HttpRequestParser::on_request_impl(bhttp::verb, beast::string_view method, beast::string_view target, int version,
                                        beast::error_code& ec) {
  if (method.size() + target.size() + 10 > limits_.max_request_line)
    return refuse(414,
                  invalid_argument("the request line is longer than the " + std::to_string(limits_.max_request_line) +
                                   " bytes this server reads; send fewer or shorter query parameters"),
                  ec);
  if (version != 10 && version != 11) return refuse(505, invalid_argument("this server speaks HTTP/1.0 and 1.1"), ec);
  head_.method = std::string(method);
  head_.target = std::string(target);
  head_.version = unsigned(version);
}

void HttpRequestParser::on_response_impl(int, beast::string_view, int, beast::error_code& ec) {
  refuse(400, invalid_argument("a response is not a request"), ec);
}

void HttpRequestParser::on_field_impl(bhttp::field, beast::string_view name, beast::string_view value,
                                      beast::error_code& ec) {
  if (++fields_ > limits_.max_header_count)
    return refuse(
        431,
        invalid_argument("the request has more than " + std::to_string(limits_.max_header_count) + " header lines"),
        ec);
  if (name.size() + value.size() + 2 > limits_.max_header_line)
    return refuse(431,
                  invalid_argument("the header '" + std::string(name.substr(0, 64)) + "' is longer than the " +
                                   std::to_string(limits_.max_header_line) + " bytes this server reads"),
                  ec);
  head_.headers.emplace_back(std::string(name), std::string(value));
}

Status HttpRequestParser::body_refusal() const {
  if (max_body_bytes_ == 0)
    return resource_exhausted(head_.method + " " + head_.target.substr(0, head_.target.find('?')) +
                              " takes no request body");
  return resource_exhausted("the request body is larger than this server accepts (" + body_limit_name_ + ", " +
                            std::to_string(max_body_bytes_) + " bytes); send fewer instances per request");
}

void HttpRequestParser::on_body_init_impl(const boost::optional<std::uint64_t>& content_length, beast::error_code& ec) {
  if (content_length && *content_length > std::uint64_t(max_body_bytes_)) refuse(413, body_refusal(), ec);
}

std::size_t HttpRequestParser::take(beast::string_view piece, beast::error_code& ec) {
  if (body_bytes_ + int64_t(piece.size()) > max_body_bytes_) {
    refuse(413, body_refusal(), ec);
    return 0;
  }
  body_bytes_ += int64_t(piece.size());
  if (sink_) {
    if (Status s = sink_(std::string_view(piece.data(), piece.size())); !s.ok()) {
      refuse(s.code() == StatusCode::kResourceExhausted ? 507 : 500, std::move(s), ec);
      return 0;
    }
  }
  return piece.size();
}

std::size_t HttpRequestParser::on_body_impl(beast::string_view body, beast::error_code& ec) { return take(body, ec); }

void HttpRequestParser::on_chunk_header_impl(std::uint64_t size, beast::string_view, beast::error_code& ec) {
  // Refused before the chunk is read: a chunk announcing more than is left is too much already.
  if (size > std::uint64_t(max_body_bytes_ - body_bytes_)) refuse(413, body_refusal(), ec);
}

std::size_t HttpRequestParser::on_chunk_body_impl(std::uint64_t, beast::string_view body, beast::error_code& ec) {
  return take(body, ec);
}

std::optional<Refusal> refusal_of(const HttpRequestParser& parser, const beast::error_code& ec,
                                  std::string_view buffered, const HttpLimits& limits) {
  if (parser.refusal()) return parser.refusal();
  if (ec == bhttp::error::header_limit || ec == bhttp::error::buffer_overflow) {
    const size_t line_end = buffered.find("\r\n");
    if (line_end == std::string_view::npos ? buffered.size() >= limits.max_request_line
                                           : line_end > limits.max_request_line)
      return Refusal{414,
                     invalid_argument("the request line is longer than the " + std::to_string(limits.max_request_line) +
                                      " bytes this server reads; send fewer or shorter query parameters")};
    return Refusal{431, invalid_argument("the request's headers are longer than the " +
                                         std::to_string(limits.max_head_bytes) + " bytes this server reads")};
  }
  if (ec == bhttp::error::bad_version) return Refusal{505, invalid_argument("this server speaks HTTP/1.0 and 1.1")};
  if (ec == bhttp::error::body_limit)
    return Refusal{413, resource_exhausted("the request body is larger than this server accepts")};
  if (ec.category() == beast::error_code(bhttp::error::end_of_stream).category() && ec != bhttp::error::end_of_stream &&
      ec != bhttp::error::partial_message && ec != bhttp::error::need_more && ec != bhttp::error::need_buffer)
    return Refusal{400, invalid_argument("the request is not valid HTTP/1.1 (" + ec.message() + ")")};
  return std::nullopt;
}

}  // namespace soiq::server::http
