#include "db/cached_value.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "db/crc32.h"

namespace soiq::db {
namespace {

static_assert(std::endian::native == std::endian::little, "cached values are stored as little-endian float64");

// Key and entry each after its length, so that moving a character from one to the other changes
// the checksum.
uint32_t value_checksum(const std::string& key, const std::string& entry, std::string_view values) {
  uint32_t crc = 0;
  for (const std::string* text : {&key, &entry}) {
    const uint64_t size = text->size();
    crc = crc32_of(std::string_view(reinterpret_cast<const char*>(&size), sizeof size), crc);
    crc = crc32_of(*text, crc);
  }
  return crc32_of(values, crc);
}

}  // namespace

std::string cached_value_bytes(const CachedFeature& f) {
  std::string out(reinterpret_cast<const char*>(f.value.data()), f.value.size() * sizeof(double));
  const uint32_t crc = value_checksum(f.key, f.entry, out);
  out.append(reinterpret_cast<const char*>(&crc), sizeof crc);
  return out;
}

bool cached_value_has_checksum(std::string_view bytes) { return bytes.size() % sizeof(double) == sizeof(uint32_t); }

std::string cached_value_damage(const CachedFeature& f, std::string_view bytes) {
  if (cached_value_has_checksum(bytes)) {
    uint32_t stored = 0;
    std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
    const uint32_t computed = value_checksum(f.key, f.entry, bytes.substr(0, bytes.size() - sizeof stored));
    if (computed == stored) return "";
    char sums[64];
    std::snprintf(sums, sizeof sums, "stored %08x, computed %08x", stored, computed);
    return std::string("checksum mismatch (crc32 ") + sums + ")";
  }
  if (bytes.size() % sizeof(double) == 0) return "";
  return std::to_string(bytes.size()) + " bytes, neither whole float64s nor whole float64s and a checksum";
}

Status set_cached_value(CachedFeature& f, std::string_view bytes) {
  const std::string damage = cached_value_damage(f, bytes);
  if (!damage.empty()) {
    return data_loss("cached feature '" + f.entry + "' under key '" + f.key + "' is corrupt: " + damage +
                     "; restore the store from a backup (soiq-admin verify lists every damaged value)");
  }
  if (cached_value_has_checksum(bytes)) bytes.remove_suffix(sizeof(uint32_t));
  f.value.resize(bytes.size() / sizeof(double));
  if (!bytes.empty()) std::memcpy(f.value.data(), bytes.data(), bytes.size());
  return ok_status();
}

}  // namespace soiq::db
