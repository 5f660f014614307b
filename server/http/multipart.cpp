#include "server/http/multipart.h"

#include <algorithm>
#include <random>

namespace soiq::server::http {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(std::string s) {
  s.erase(0, s.find_first_not_of(" \t"));
  s.erase(s.find_last_not_of(" \t") + 1);
  return s;
}

constexpr size_t kMaxPartHeaderBytes = 8 << 10;

}  // namespace

bool is_multipart_related(const std::string& content_type) {
  return lower(trim(content_type.substr(0, content_type.find(';')))) == "multipart/related";
}

std::string header_parameter(const std::string& value, const std::string& name) {
  size_t at = value.find(';');
  while (at != std::string::npos) {
    const size_t next = value.find(';', at + 1);
    // A quoted value may hold ';': find the end of this parameter by its quotes.
    std::string item = value.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
    const size_t eq = item.find('=');
    if (eq != std::string::npos && lower(trim(item.substr(0, eq))) == lower(name)) {
      std::string v = trim(value.substr(at + 1 + eq + 1));
      if (!v.empty() && v[0] == '"') {
        const size_t close = v.find('"', 1);
        return v.substr(1, close == std::string::npos ? std::string::npos : close - 1);
      }
      return trim(v.substr(0, v.find(';')));
    }
    at = next;
  }
  return "";
}

Result<ParsedMultipart> parse_multipart_related(const std::string& content_type, std::string_view body,
                                                size_t max_parts) {
  const std::string boundary = header_parameter(content_type, "boundary");
  if (boundary.empty() || boundary.size() > 70)
    return invalid_argument("the multipart/related Content-Type has no boundary (RFC 2046: 1 to 70 characters)");
  ParsedMultipart out;
  out.type = lower(header_parameter(content_type, "type"));
  const std::string delimiter = "--" + boundary;
  size_t at = body.find(delimiter);
  if (at == std::string_view::npos) return invalid_argument("the body does not contain its boundary");
  while (true) {
    at += delimiter.size();
    if (body.substr(at, 2) == "--") break;  // the close delimiter
    // The rest of the delimiter line (transport padding), then the part's headers.
    const size_t line_end = body.find("\r\n", at);
    if (line_end == std::string_view::npos) return invalid_argument("a multipart boundary line does not end");
    const size_t headers_start = line_end + 2;
    // A part without headers has its blank line right after the boundary line.
    const size_t headers_end = body.find("\r\n\r\n", line_end);
    const size_t header_bytes =
        headers_end != std::string_view::npos && headers_end > headers_start ? headers_end - headers_start : 0;
    if (headers_end == std::string_view::npos || header_bytes > kMaxPartHeaderBytes)
      return invalid_argument("part " + std::to_string(out.parts.size() + 1) + " has no end of its headers");
    MultipartPart part;
    const std::string headers(body.substr(headers_start, header_bytes));
    size_t line = 0;
    while (line < headers.size()) {
      size_t end = headers.find("\r\n", line);
      if (end == std::string::npos) end = headers.size();
      const std::string h = headers.substr(line, end - line);
      const size_t colon = h.find(':');
      if (colon != std::string::npos && lower(trim(h.substr(0, colon))) == "content-type")
        part.content_type = lower(trim(h.substr(colon + 1)));
      line = end + 2;
    }
    const size_t data_start = headers_end + 4;
    const size_t next = body.find("\r\n" + delimiter, data_start);
    if (next == std::string_view::npos)
      return invalid_argument("part " + std::to_string(out.parts.size() + 1) + " does not end with the boundary");
    part.bytes = body.substr(data_start, next - data_start);
    if (out.parts.size() == max_parts)
      return invalid_argument("more than " + std::to_string(max_parts) + " parts in one request");
    out.parts.push_back(std::move(part));
    at = next + 2;
  }
  return out;
}

std::string random_boundary() {
  std::random_device rd;
  static constexpr char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string boundary = "soiq-";
  for (int i = 0; i < 32; ++i) boundary += kAlphabet[rd() % 36];
  return boundary;
}

std::string multipart_part_head(const std::string& boundary, const std::string& part_type, bool first) {
  return (first ? "--" : "\r\n--") + boundary + "\r\nContent-Type: " + part_type + "\r\n\r\n";
}

Status check_part_against_boundary(const std::string& boundary, std::string_view part) {
  if (part.find(boundary) == std::string_view::npos) return ok_status();
  return internal_error("a part holds the multipart boundary chosen at random; ask again");
}

std::string multipart_close(const std::string& boundary, bool any_part) {
  return (any_part ? "\r\n--" : "--") + boundary + "--\r\n";
}

WrittenMultipart write_multipart_related(std::vector<std::string> parts, const std::string& part_type) {
  WrittenMultipart out;
  do {
    out.boundary = random_boundary();
  } while (std::any_of(parts.begin(), parts.end(),
                       [&](const std::string& p) { return !check_part_against_boundary(out.boundary, p).ok(); }));
  out.pieces.reserve(2 * parts.size() + 1);
  for (size_t i = 0; i < parts.size(); ++i) {
    out.pieces.push_back(multipart_part_head(out.boundary, part_type, i == 0));
    out.pieces.push_back(std::move(parts[i]));
  }
  out.pieces.push_back(multipart_close(out.boundary, !parts.empty()));
  return out;
}

std::string WrittenMultipart::body() const {
  std::string out;
  for (const std::string& p : pieces) out += p;
  return out;
}

}  // namespace soiq::server::http
