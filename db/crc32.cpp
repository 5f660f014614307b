#include "db/crc32.h"

#include <zlib.h>

#include <algorithm>

namespace soiq::db {

uint32_t crc32_of(std::string_view bytes, uint32_t crc) {
  // zlib takes a uInt length: feed it in pieces.
  uLong sum = crc;
  const auto* p = reinterpret_cast<const Bytef*>(bytes.data());
  size_t left = bytes.size();
  while (left > 0) {
    const uInt n = uInt(std::min<size_t>(left, size_t(1) << 30));
    sum = crc32(sum, p, n);
    p += n;
    left -= n;
  }
  return uint32_t(sum);
}

}  // namespace soiq::db
