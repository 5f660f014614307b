#pragma once
// A lossless stream codec for arrays of fixed-width integers that change little from one element to
// the next: a stored surface's vertex coordinates (float64 bit patterns) and triangle corners (int32).
//
// Encoding, per block of kBlockBytes: each value's difference to the one before it (wrapping; the
// first of the array to 0), for 4-byte values zigzagged so small negative steps have small codes
// (for float64 bit patterns it measured worse: its shift moves mantissa noise across the bytes),
// then byte-shuffled (all the lowest bytes, then all the next ones: the high bytes of small steps
// are zero runs), then LZ4 (Debian's liblz4), or stored as is when LZ4 does not make it smaller.
// A block is [uint32 size | flag bit 31: stored][bytes]; blocks follow one another.
// Decoding writes each value straight to its place in the caller's array (`stride` bytes apart), so
// a block's bytes are touched while they are in cache and no whole-array buffer is needed.
//
// Inputs   `count` values of `width` bytes (4 or 8), the first at `values`, `stride` bytes apart
//          (>= width; e.g. 24 for one coordinate of an array of Vec3).
// Errors   read_delta_planes: DATA_LOSS when the stream is truncated, a block's size is out of
//          range, or a block does not decode to exactly its values' bytes (a corrupt blob).
// Cost     O(count); no allocation beyond one block's scratch. Thread-safe.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/base/status.h"

namespace soiq::db {

// 65536 float64 or 131072 int32: 512 KiB of shuffled bytes, which stays in a core's L2 while it is
// decoded. Measured (soiq-bench codec): 64 KiB blocks made a 100k-triangle surface 40 % larger
// (LZ4 found fewer of the long runs), 1 MiB ones were no smaller and no faster.
inline constexpr size_t kBlockBytes = 512 * 1024;

void append_delta_planes(const void* values, size_t count, int width, size_t stride, std::string& out);

// Reads what append_delta_planes wrote from `in` at `at` (advanced past it) into `values`.
Status read_delta_planes(std::string_view in, size_t& at, size_t count, int width, size_t stride, void* values);

}  // namespace soiq::db
