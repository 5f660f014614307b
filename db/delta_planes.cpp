#include "db/delta_planes.h"

#include <lz4.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <type_traits>

#include "core/base/cpu_dispatch.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace soiq::db {
namespace {

constexpr uint32_t kStoredFlag = 1u << 31;

// Zigzag for 4-byte values only (delta_planes.h says why).
template <typename U>
U zigzag(U d) {
  if constexpr (sizeof(U) == 8) return d;
  using S = std::make_signed_t<U>;
  return U(d << 1) ^ U(S(d) >> (sizeof(U) * 8 - 1));
}

template <typename U>
U unzigzag(U z) {
  if constexpr (sizeof(U) == 8) return z;
  return U(z >> 1) ^ U(U(0) - (z & 1));
}

template <typename U>
U load(const uint8_t* p) {
  U v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <typename U>
void encode(const uint8_t* values, size_t count, size_t stride, std::string& out) {
  constexpr size_t kWidth = sizeof(U);
  constexpr size_t kPerBlock = kBlockBytes / kWidth;
  // Buffers of the largest block this array has, not of kBlockBytes, and not zeroed: most arrays
  // are small, and zeroing half a megabyte twice per array was most of encoding a small mesh.
  const size_t largest = std::min(kPerBlock, count) * kWidth;
  std::unique_ptr<uint8_t[]> planes(new uint8_t[largest]);
  const int bound = LZ4_compressBound(int(largest));
  std::unique_ptr<char[]> compressed(new char[size_t(bound)]);
  U prev = 0;
  for (size_t from = 0; from < count; from += kPerBlock) {
    const size_t n = std::min(kPerBlock, count - from);
    for (size_t i = 0; i < n; ++i) {
      const U v = load<U>(values + (from + i) * stride);
      const U z = zigzag(U(v - prev));
      prev = v;
      for (size_t b = 0; b < kWidth; ++b) planes[b * n + i] = uint8_t(z >> (8 * b));
    }
    const int raw = int(n * kWidth);
    const int size = LZ4_compress_default(reinterpret_cast<const char*>(planes.get()), compressed.get(), raw, bound);
    const bool stored = size <= 0 || size >= raw;
    const uint32_t header = stored ? uint32_t(raw) | kStoredFlag : uint32_t(size);
    out.append(reinterpret_cast<const char*>(&header), sizeof header);
    if (stored) {
      out.append(reinterpret_cast<const char*>(planes.get()), size_t(raw));
    } else {
      out.append(compressed.get(), size_t(size));
    }
  }
}

// Gathers values [i, i + 16) of a block of `n` shuffled values into `group` (16 values, each in
// native byte order). SSE2 transposes 16 bytes of each plane at once; that is most of the decoding.
template <typename U>
void gather16(const uint8_t* planes, size_t n, size_t i, U* group) {
#if defined(__SSE2__)
  if constexpr (sizeof(U) == 8) {
    __m128i p[8];
    for (int b = 0; b < 8; ++b) p[b] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(planes + b * n + i));
    // Bytes of planes (0,1), (2,3), (4,5), (6,7) interleaved: 16-bit pairs per value.
    const __m128i a0 = _mm_unpacklo_epi8(p[0], p[1]), a1 = _mm_unpackhi_epi8(p[0], p[1]);
    const __m128i b0 = _mm_unpacklo_epi8(p[2], p[3]), b1 = _mm_unpackhi_epi8(p[2], p[3]);
    const __m128i c0 = _mm_unpacklo_epi8(p[4], p[5]), c1 = _mm_unpackhi_epi8(p[4], p[5]);
    const __m128i d0 = _mm_unpacklo_epi8(p[6], p[7]), d1 = _mm_unpackhi_epi8(p[6], p[7]);
    // Then 32-bit halves: bytes 0-3 (e) and 4-7 (f) of values 0-3, 4-7, 8-11, 12-15.
    const __m128i e0 = _mm_unpacklo_epi16(a0, b0), e1 = _mm_unpackhi_epi16(a0, b0);
    const __m128i e2 = _mm_unpacklo_epi16(a1, b1), e3 = _mm_unpackhi_epi16(a1, b1);
    const __m128i f0 = _mm_unpacklo_epi16(c0, d0), f1 = _mm_unpackhi_epi16(c0, d0);
    const __m128i f2 = _mm_unpacklo_epi16(c1, d1), f3 = _mm_unpackhi_epi16(c1, d1);
    // Then whole values, two per register.
    __m128i* out = reinterpret_cast<__m128i*>(group);
    _mm_storeu_si128(out + 0, _mm_unpacklo_epi32(e0, f0));
    _mm_storeu_si128(out + 1, _mm_unpackhi_epi32(e0, f0));
    _mm_storeu_si128(out + 2, _mm_unpacklo_epi32(e1, f1));
    _mm_storeu_si128(out + 3, _mm_unpackhi_epi32(e1, f1));
    _mm_storeu_si128(out + 4, _mm_unpacklo_epi32(e2, f2));
    _mm_storeu_si128(out + 5, _mm_unpackhi_epi32(e2, f2));
    _mm_storeu_si128(out + 6, _mm_unpacklo_epi32(e3, f3));
    _mm_storeu_si128(out + 7, _mm_unpackhi_epi32(e3, f3));
    return;
  } else {
    __m128i p[4];
    for (int b = 0; b < 4; ++b) p[b] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(planes + b * n + i));
    const __m128i a0 = _mm_unpacklo_epi8(p[0], p[1]), a1 = _mm_unpackhi_epi8(p[0], p[1]);
    const __m128i b0 = _mm_unpacklo_epi8(p[2], p[3]), b1 = _mm_unpackhi_epi8(p[2], p[3]);
    __m128i* out = reinterpret_cast<__m128i*>(group);
    _mm_storeu_si128(out + 0, _mm_unpacklo_epi16(a0, b0));
    _mm_storeu_si128(out + 1, _mm_unpackhi_epi16(a0, b0));
    _mm_storeu_si128(out + 2, _mm_unpacklo_epi16(a1, b1));
    _mm_storeu_si128(out + 3, _mm_unpackhi_epi16(a1, b1));
    return;
  }
#endif
  for (size_t k = 0; k < 16; ++k) {
    U z = 0;
    for (size_t b = 0; b < sizeof(U); ++b) z |= U(planes[b * n + i + k]) << (8 * b);
    group[k] = z;
  }
}

// One block's scratch per thread, kept: a fresh allocation this large is fresh pages from the
// kernel each time, whose faults cost more than decoding a small surface.
uint8_t* scratch() {
  thread_local std::unique_ptr<uint8_t[]> buffer(new uint8_t[kBlockBytes]);
  return buffer.get();
}

template <typename U>
Status decode(std::string_view in, size_t& at, size_t count, size_t stride, uint8_t* values) {
  constexpr size_t kWidth = sizeof(U);
  constexpr size_t kPerBlock = kBlockBytes / kWidth;
  uint8_t* const planes = scratch();
  U prev = 0;
  for (size_t from = 0; from < count; from += kPerBlock) {
    const size_t n = std::min(kPerBlock, count - from);
    const size_t raw = n * kWidth;
    uint32_t header;
    if (in.size() - at < sizeof header) return data_loss("blob is truncated (a block header is missing)");
    std::memcpy(&header, in.data() + at, sizeof header);
    at += sizeof header;
    const size_t size = header & ~kStoredFlag;
    if (size > in.size() - at || size > size_t(LZ4_compressBound(int(kBlockBytes))))
      return data_loss("blob is truncated (a block says " + std::to_string(size) + " bytes)");
    const uint8_t* shuffled = reinterpret_cast<const uint8_t*>(in.data() + at);
    if (header & kStoredFlag) {
      if (size != raw) return data_loss("blob has a stored block of the wrong size");
    } else {
      const int got = LZ4_decompress_safe(in.data() + at, reinterpret_cast<char*>(planes), int(size), int(raw));
      if (got != int(raw)) return data_loss("blob has a corrupt block");
      shuffled = planes;
    }
    at += size;
    uint8_t* dst = values + from * stride;
    size_t i = 0;
    alignas(16) U group[16];
    for (; i + 16 <= n; i += 16) {
      gather16<U>(shuffled, n, i, group);
      for (size_t k = 0; k < 16; ++k) {
        prev = U(prev + unzigzag(group[k]));
        std::memcpy(dst + (i + k) * stride, &prev, kWidth);
      }
    }
    for (; i < n; ++i) {
      U z = 0;
      for (size_t b = 0; b < kWidth; ++b) z |= U(shuffled[b * n + i]) << (8 * b);
      prev = U(prev + unzigzag(z));
      std::memcpy(dst + i * stride, &prev, kWidth);
    }
  }
  return ok_status();
}

}  // namespace

void append_delta_planes(const void* values, size_t count, int width, size_t stride, std::string& out) {
  const auto* p = static_cast<const uint8_t*>(values);
  if (width == 8) {
    encode<uint64_t>(p, count, stride, out);
  } else {
    encode<uint32_t>(p, count, stride, out);
  }
}

Status read_delta_planes(std::string_view in, size_t& at, size_t count, int width, size_t stride, void* values) {
  auto* p = static_cast<uint8_t*>(values);
  // The transposes and prefix sums compiled for the CPU (cpu_dispatch.h): AVX encodes the same
  // SSE2 steps in fewer instructions; LZ4 is the library's own.
  return cpu_dispatch([&] {
    return width == 8 ? decode<uint64_t>(in, at, count, stride, p) : decode<uint32_t>(in, at, count, stride, p);
  });
}

}  // namespace soiq::db
