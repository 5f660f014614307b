#pragma once
// Loads a scalar stored in a given byte order from unaligned bytes, for the binary mesh formats
// (STL is little-endian, PLY either). memcpy keeps it free of alignment and aliasing faults.
// The caller checks that sizeof(T) bytes are there. O(1); thread-safe.

#include <algorithm>
#include <bit>
#include <cstring>

namespace soiq {

template <typename T>
T load_scalar(const char* bytes, bool big_endian) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, bytes, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return value;
}

}  // namespace soiq
