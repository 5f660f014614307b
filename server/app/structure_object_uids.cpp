#include "server/app/structure_object_uids.h"

#include "db/sha256.h"

namespace soiq::server {
namespace {

using u128 = unsigned __int128;

constexpr char kRoot[] = "2.25.";
constexpr int64_t kMaxId = (int64_t(1) << 47) - 1;

std::string decimal(u128 v) {
  if (v == 0) return "0";
  std::string out;
  while (v > 0) {
    out.insert(out.begin(), char('0' + int(v % 10)));
    v /= 10;
  }
  return out;
}

// Bits, from the most significant: 1 object | 47 id | 4 version (8) | 1 kind | 11 hash | 2 variant
// (10) | 62 hash.
u128 uuid_of(db::StructureObject object, int64_t id, bool instance, uint64_t hash) {
  u128 v = u128(object == db::StructureObject::kRtStruct ? 1 : 0) << 127;
  v |= u128(uint64_t(id)) << 80;
  v |= u128(8) << 76;
  v |= u128(instance ? 1 : 0) << 75;
  v |= u128((hash >> 53) & 0x7FF) << 64;
  v |= u128(2) << 62;
  v |= u128(hash & ((uint64_t(1) << 62) - 1));
  return v;
}

// Each object hashes under its own salt, so its UIDs share no hash bits with the other's.
const char* salt(db::StructureObject object) {
  return object == db::StructureObject::kSeg ? "soiq structure SEG\n" : "soiq structure RTSTRUCT\n";
}

uint64_t content_hash(const db::StructureRecord& s, db::StructureObject object) {
  db::Sha256 h;
  const std::string text =
      salt(object) + std::to_string(s.id) + "\n" + s.surface.sha256 + "\n" + s.source_series_uid + "\n" + s.name;
  h.update(text.data(), text.size());
  const std::string hex = h.hex_digest();
  return std::stoull(hex.substr(0, 16), nullptr, 16);
}

}  // namespace

StructureObjectUids structure_object_uids(const db::StructureRecord& s, db::StructureObject object) {
  const uint64_t hash = content_hash(s, object);
  const int64_t id = s.id > 0 && s.id <= kMaxId ? s.id : 0;
  return {kRoot + decimal(uuid_of(object, id, false, hash)), kRoot + decimal(uuid_of(object, id, true, hash))};
}

std::optional<ParsedStructureUid> parse_structure_object_uid(const std::string& uid) {
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
  const int64_t id = int64_t(uint64_t(v >> 80) & uint64_t(kMaxId));
  if (id <= 0) return std::nullopt;
  return ParsedStructureUid{id, (v >> 127) != 0 ? db::StructureObject::kRtStruct : db::StructureObject::kSeg,
                            ((v >> 75) & 1) != 0};
}

}  // namespace soiq::server
