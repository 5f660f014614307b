#include "server/http/http_range.h"

#include <charconv>
#include <optional>
#include <string_view>
#include <vector>

#include "server/http/http_status.h"

namespace soiq::server::http {
namespace {

struct Spec {
  std::optional<int64_t> first, last;  // "a-b", "a-" (no last), "-n" (no first: the last n bytes)
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::optional<int64_t> number(std::string_view s) {
  if (s.empty()) return std::nullopt;
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v < 0) return std::nullopt;
  return v;
}

// The ranges of "bytes=..."; nullopt when the header does not parse (then it is ignored). Counting
// stops past `max_ranges`, so a header of thousands of ranges costs no more than a few.
std::optional<std::vector<Spec>> parse(std::string_view header, int max_ranges) {
  header = trim(header);
  if (header.substr(0, 6) != "bytes=") return std::nullopt;
  header.remove_prefix(6);
  std::vector<Spec> out;
  while (true) {
    const size_t comma = header.find(',');
    const std::string_view item = trim(header.substr(0, comma));
    const size_t dash = item.find('-');
    if (dash == std::string_view::npos) return std::nullopt;
    Spec s;
    s.first = number(item.substr(0, dash));
    s.last = number(item.substr(dash + 1));
    if ((!s.first && !s.last) || (dash > 0 && !s.first) || (dash + 1 < item.size() && !s.last) ||
        (s.first && s.last && *s.last < *s.first))
      return std::nullopt;
    out.push_back(s);
    if (int(out.size()) > max_ranges || comma == std::string_view::npos) return out;
    header.remove_prefix(comma + 1);
  }
}

void refuse(HttpReply& reply, int64_t length, const std::string& why) {
  reply = HttpReply{416, "application/json", error_body(invalid_argument(why), 416), {}};
  reply.headers.emplace("Content-Range", "bytes */" + std::to_string(length));
}

}  // namespace

void apply_range(const std::string& range_header, int max_ranges, HttpReply& reply) {
  if (range_header.empty() || reply.status != 200) return;
  const std::optional<std::vector<Spec>> specs = parse(range_header, max_ranges);
  if (!specs) return;
  const int64_t length = reply.size();
  if (int(specs->size()) > max_ranges)
    return refuse(reply, length,
                  "this server serves at most " + std::to_string(max_ranges) + " byte range per request");
  const Spec& s = specs->front();
  int64_t first = 0, last = length - 1;
  if (!s.first) {
    first = std::max<int64_t>(0, length - *s.last);
  } else {
    first = *s.first;
    if (s.last) last = std::min(*s.last, length - 1);
  }
  if (length == 0 || first >= length || (!s.first && *s.last == 0))
    return refuse(reply, length, "the range asked lies past the end of the " + std::to_string(length) + "-byte answer");
  // The range's bytes, gathered from the body and its pieces.
  std::string out;
  out.reserve(size_t(last - first + 1));
  int64_t at = 0;
  auto take = [&](const std::string& piece) {
    const int64_t from = std::max<int64_t>(first, at), to = std::min<int64_t>(last + 1, at + int64_t(piece.size()));
    if (from < to) out.append(piece, size_t(from - at), size_t(to - from));
    at += int64_t(piece.size());
  };
  take(reply.body);
  for (const std::string& p : reply.pieces) take(p);
  reply.status = 206;
  reply.body = std::move(out);
  reply.pieces.clear();
  reply.headers.emplace("Content-Range",
                        "bytes " + std::to_string(first) + "-" + std::to_string(last) + "/" + std::to_string(length));
}

}  // namespace soiq::server::http
