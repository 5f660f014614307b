#include "server/app/structure_seg_uids.h"

#include "db/sha256.h"

namespace soiq::server {
namespace {

using u128 = unsigned __int128;

constexpr char kRoot[] = "2.25.";
constexpr int64_t kMaxId = (int64_t(1) << 48) - 1;

std::string decimal(u128 v) {
  if (v == 0) return "0";
  std::string out;
  while (v > 0) {
    out.insert(out.begin(), char('0' + int(v % 10)));
    v /= 10;
  }
  return out;
}

// Bits, from the most significant: 48 id | 4 version (8) | 1 kind | 11 hash | 2 variant (10) | 62 hash.
u128 uuid_of(int64_t id, bool instance, uint64_t hash) {
  u128 v = u128(uint64_t(id)) << 80;
  v |= u128(8) << 76;
  v |= u128(instance ? 1 : 0) << 75;
  v |= u128((hash >> 53) & 0x7FF) << 64;
  v |= u128(2) << 62;
  v |= u128(hash & ((uint64_t(1) << 62) - 1));
  return v;
}

uint64_t content_hash(const db::StructureRecord& s) {
  db::Sha256 h;
  const std::string text = "soiq structure SEG\n" + std::to_string(s.id) + "\n" + s.surface.sha256 + "\n" +
                           s.source_series_uid + "\n" + s.name;
  h.update(text.data(), text.size());
  const std::string hex = h.hex_digest();
  return std::stoull(hex.substr(0, 16), nullptr, 16);
}

}  // namespace

StructureSegUids structure_seg_uids(const db::StructureRecord& s) {
  const uint64_t hash = content_hash(s);
  const int64_t id = s.id > 0 && s.id <= kMaxId ? s.id : 0;
  return {kRoot + decimal(uuid_of(id, false, hash)), kRoot + decimal(uuid_of(id, true, hash))};
}

std::optional<ParsedSegUid> parse_structure_seg_uid(const std::string& uid) {
  if (uid.rfind(kRoot, 0) != 0) return std::nullopt;
  const std::string digits = uid.substr(sizeof kRoot - 1);
  if (digits.empty() || digits.size() > 39 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
  u128 v = 0;
  for (const char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;
    const u128 next = v * 10 + u128(c - '0');
    if (next / 10 != v) return std::nullopt;  // past 2^128
    v = next;
  }
  if (((v >> 76) & 0xF) != 8 || ((v >> 62) & 0x3) != 2) return std::nullopt;
  const int64_t id = int64_t(uint64_t(v >> 80));
  if (id <= 0) return std::nullopt;
  return ParsedSegUid{id, ((v >> 75) & 1) != 0};
}

}  // namespace soiq::server
