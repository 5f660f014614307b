#include "server/http/http_request.h"

#include <strings.h>

namespace soiq::server::http {
namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Percent-decodes `in`; in a query, '+' is a space (HTML forms and every HTTP client library send
// it so). A NUL could cut a name short where C strings are used, so it is refused.
Result<std::string> decode(std::string_view in, bool query) {
  std::string out;
  out.reserve(in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    const char c = in[i];
    if (c == '%') {
      const bool whole = i + 2 < in.size();
      const int hi = whole ? hex_digit(in[i + 1]) : -1;
      const int lo = whole ? hex_digit(in[i + 2]) : -1;
      if (hi < 0 || lo < 0)
        return invalid_argument("the request target has a malformed percent escape at '" +
                                std::string(in.substr(i, 3)) + "'");
      const char decoded = char(hi * 16 + lo);
      if (decoded == '\0') return invalid_argument("the request target holds an encoded NUL (%00)");
      out += decoded;
      i += 2;
    } else {
      out += query && c == '+' ? ' ' : c;
    }
  }
  return out;
}

}  // namespace

bool HttpRequest::has_header(std::string_view name) const {
  for (const auto& [k, v] : headers)
    if (k.size() == name.size() && strncasecmp(k.data(), name.data(), k.size()) == 0) return true;
  return false;
}

std::string HttpRequest::header(std::string_view name) const {
  for (const auto& [k, v] : headers)
    if (k.size() == name.size() && strncasecmp(k.data(), name.data(), k.size()) == 0) return v;
  return "";
}

Status parse_target(const std::string& target, std::string& path, QueryParams& params) {
  if (target.empty() || target.front() != '/')
    return invalid_argument("the request target must be a path starting with '/'");
  const size_t question = target.find('?');
  const std::string_view raw_path = std::string_view(target).substr(0, question);
  SOIQ_ASSIGN_OR_RETURN(path, decode(raw_path, false));
  params.clear();
  if (question == std::string::npos) return ok_status();
  std::string_view query = std::string_view(target).substr(question + 1);
  const size_t hash = query.find('#');
  if (hash != std::string_view::npos) query = query.substr(0, hash);
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
    if (pair.empty()) continue;
    const size_t eq = pair.find('=');
    SOIQ_ASSIGN_OR_RETURN(std::string name, decode(pair.substr(0, eq), true));
    std::string value;
    if (eq != std::string_view::npos) {
      SOIQ_ASSIGN_OR_RETURN(value, decode(pair.substr(eq + 1), true));
    }
    params.emplace_back(std::move(name), std::move(value));
  }
  return ok_status();
}

}  // namespace soiq::server::http
