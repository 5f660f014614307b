#pragma once
// The checksum of stored bytes that soiq checks on every read (surface blobs of version 3,
// surface_blob.h; cached feature values, cached_value.h): CRC-32 (ISO-HDLC, zlib's crc32).
//
// Why CRC-32: it detects every single flipped bit and every burst of up to 32 flipped bits in a
// blob of any length, the damage a disk or a memory error does, which Adler-32 and the xxHash
// family only detect with high probability; zlib is linked already. Its crc32 runs at ~6 GB/s
// here: 14 % of a surface blob's decode, where XXH3 would cost 5 % (docs/ARCHITECTURE.md "Stored
// bytes").
//
// crc32_of(bytes, crc)  the CRC-32 of `bytes`, continuing `crc` (the CRC of the bytes before them;
//                       0 to start), so a checksum may cover pieces that are not contiguous.
// Cost O(size). Thread-safe.

#include <cstdint>
#include <string_view>

namespace soiq::db {

uint32_t crc32_of(std::string_view bytes, uint32_t crc = 0);

}  // namespace soiq::db
