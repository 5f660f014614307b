#include "core/io/zlib_codec.h"

#include <zlib.h>

#include <algorithm>

namespace soiq {

namespace {

// Inflates into at most `limit` bytes. `exact`: the stream must hold exactly `limit` bytes (an
// announced size); otherwise inflation stops at `limit` or at the end of the stream, whichever
// comes first. The output buffer grows with what the stream really yields, up to `limit`: a tiny
// file whose header announces gigabytes fails as truncated without allocating them first.
Result<std::string> inflate_up_to(std::string_view compressed, size_t limit, bool exact, const std::string& name) {
  const size_t expected_bytes = limit;
  std::string out(std::min<size_t>(limit, size_t(1) << 20), '\0');
  z_stream zs{};
  // 32 + MAX_WBITS: accept both zlib and gzip headers.
  if (inflateInit2(&zs, 32 + MAX_WBITS) != Z_OK) return internal_error("zlib inflateInit2 failed for '" + name + "'");
  size_t in_pos = 0;
  size_t out_pos = 0;
  char spare = 0;
  while (true) {
    // zlib counts in uInt: feed at most 1 GiB per call. Once the output is full, a one-byte spare
    // buffer reveals a stream that holds more than announced.
    const size_t in_chunk = std::min<size_t>(compressed.size() - in_pos, size_t(1) << 30);
    if (out_pos == out.size() && out.size() < limit) out.resize(std::min(limit, out.size() * 2));
    const bool full = out_pos == limit;
    const size_t out_chunk = full ? 1 : std::min<size_t>(out.size() - out_pos, size_t(1) << 30);
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + in_pos));
    zs.avail_in = uInt(in_chunk);
    zs.next_out = reinterpret_cast<Bytef*>(full ? &spare : out.data() + out_pos);
    zs.avail_out = uInt(out_chunk);
    const int rc = inflate(&zs, Z_NO_FLUSH);
    in_pos += in_chunk - zs.avail_in;
    const size_t produced = out_chunk - zs.avail_out;
    if (full && produced > 0) {
      inflateEnd(&zs);
      if (!exact) return out;
      return invalid_argument("compressed data of '" + name + "' holds more than the " +
                              std::to_string(expected_bytes) + " bytes its header announces");
    }
    if (!full) out_pos += produced;
    if (rc == Z_STREAM_END) {
      if (out_pos == limit || in_pos >= compressed.size()) break;
      if (inflateReset(&zs) != Z_OK) break;  // another gzip member follows
      continue;
    }
    if (rc == Z_BUF_ERROR) break;  // no progress possible: the input is exhausted
    if (rc != Z_OK) {
      const std::string why = zs.msg ? zs.msg : "error " + std::to_string(rc);
      inflateEnd(&zs);
      return invalid_argument("compressed data of '" + name + "' is corrupt (zlib: " + why + ")");
    }
  }
  inflateEnd(&zs);
  if (!exact) {
    out.resize(out_pos);
    return out;
  }
  if (out_pos != limit) {
    return invalid_argument("compressed data of '" + name + "' is truncated: it inflates to " +
                            std::to_string(out_pos) + " bytes, expected " + std::to_string(expected_bytes));
  }
  return out;
}

}  // namespace

Result<std::string> inflate_bytes(std::string_view compressed, size_t expected_bytes, const std::string& name) {
  return inflate_up_to(compressed, expected_bytes, /*exact=*/true, name);
}

Result<std::string> inflate_at_most(std::string_view compressed, size_t max_bytes, const std::string& name) {
  return inflate_up_to(compressed, max_bytes, /*exact=*/false, name);
}

Result<std::string> deflate_bytes(std::string_view data, ZlibFormat format) {
  z_stream zs{};
  const int window_bits = format == ZlibFormat::kGzip ? 16 + MAX_WBITS : MAX_WBITS;
  if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, window_bits, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    return internal_error("zlib deflateInit2 failed");
  }
  std::string out;
  size_t in_pos = 0;
  char buffer[1 << 16];
  int rc = Z_OK;
  do {
    const size_t in_chunk = std::min<size_t>(data.size() - in_pos, 1u << 30);
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + in_pos));
    zs.avail_in = uInt(in_chunk);
    const bool last = in_pos + in_chunk == data.size();
    do {
      zs.next_out = reinterpret_cast<Bytef*>(buffer);
      zs.avail_out = sizeof buffer;
      rc = deflate(&zs, last ? Z_FINISH : Z_NO_FLUSH);
      if (rc == Z_STREAM_ERROR) {
        deflateEnd(&zs);
        return internal_error("zlib deflate failed");
      }
      out.append(buffer, sizeof buffer - zs.avail_out);
    } while (zs.avail_out == 0);
    in_pos += in_chunk;
  } while (rc != Z_STREAM_END);
  deflateEnd(&zs);
  return out;
}

}  // namespace soiq
