#include "db/page_token.h"

#include <cstdint>

namespace soiq::db {
namespace {

constexpr char kHex[] = "0123456789abcdef";

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

std::string to_hex(std::string_view bytes) {
  std::string out;
  out.reserve(2 * bytes.size());
  for (unsigned char c : bytes) {
    out += kHex[c >> 4];
    out += kHex[c & 0xf];
  }
  return out;
}

}  // namespace

Result<int> effective_page_size(int32_t requested) {
  if (requested < 0) return invalid_argument("page_size must be >= 0, got " + std::to_string(requested));
  if (requested == 0) return 100;
  return requested > 1000 ? 1000 : int(requested);
}

std::string make_page_token(std::string_view list, std::string_view last_key) {
  // "v1" lets a later encoding tell its own tokens apart.
  return "v1" + to_hex(list) + "." + to_hex(last_key);
}

Result<std::string> parse_page_token(std::string_view list, const std::string& token) {
  if (token.empty()) return std::string();
  const std::string prefix = "v1" + to_hex(list) + ".";
  const auto bad = [&] {
    return invalid_argument(
        "page_token is not a token of this list; pass the next_page_token of the previous "
        "response unchanged, or none for the first page");
  };
  if (token.compare(0, prefix.size(), prefix) != 0) return bad();
  const std::string_view hex = std::string_view(token).substr(prefix.size());
  if (hex.empty() || hex.size() % 2 != 0) return bad();
  std::string key;
  key.reserve(hex.size() / 2);
  for (size_t i = 0; i < hex.size(); i += 2) {
    const int hi = hex_value(hex[i]), lo = hex_value(hex[i + 1]);
    if (hi < 0 || lo < 0) return bad();
    key += char(hi * 16 + lo);
  }
  return key;
}

}  // namespace soiq::db
