#include "db/cached_value.h"

#include <bit>
#include <cstring>
#include <string>

namespace soiq::db {

static_assert(std::endian::native == std::endian::little, "cached values are stored as little-endian float64");

std::string_view cached_value_bytes(const std::vector<double>& value) {
  return {reinterpret_cast<const char*>(value.data()), value.size() * sizeof(double)};
}

Status set_cached_value(CachedFeature& f, std::string_view bytes) {
  if (bytes.size() % sizeof(double) != 0) {
    return data_loss("cached feature '" + f.entry + "' under key '" + f.key + "' has " + std::to_string(bytes.size()) +
                     " bytes, not a whole number of float64");
  }
  f.value.resize(bytes.size() / sizeof(double));
  if (!bytes.empty()) std::memcpy(f.value.data(), bytes.data(), bytes.size());
  return ok_status();
}

}  // namespace soiq::db
