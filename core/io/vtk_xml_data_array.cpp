#include "core/io/vtk_xml_data_array.h"

#include <lz4.h>
#include <lzma.h>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/io/byte_order.h"
#include "core/io/zlib_codec.h"

namespace soiq {
namespace {

std::string count_text(uint64_t n) { return std::to_string(n); }

// Reads the bytes of an array in order, from raw bytes or from base64 text. Base64 is decoded
// quantum by quantum with padding allowed in the middle: VTK encodes the header and the data as
// two runs (the header's run ends in '=' padding), other writers as one; both decode the same.
class ByteReader {
 public:
  ByteReader(std::string_view source, bool base64) : source_(source), base64_(base64) {}

  // An upper bound of the bytes left, known without decoding: sizes are checked against it.
  uint64_t most_left() const {
    const uint64_t chars = source_.size() - position_;
    return base64_ ? chars / 4 * 3 + (pending_.size() - pending_used_) : chars;
  }

  // Appends the next `n` bytes to `out`; the caller has checked `n` against most_left().
  Status take(uint64_t n, std::string& out, const std::string& what) {
    if (!base64_) {
      if (n > source_.size() - position_) return truncated(what);
      out.append(source_.substr(position_, n));
      position_ += n;
      return ok_status();
    }
    while (n > 0) {
      if (pending_used_ == pending_.size()) SOIQ_RETURN_IF_ERROR(decode_quantum(what));
      const size_t k = std::min<uint64_t>(n, pending_.size() - pending_used_);
      out.append(pending_, pending_used_, k);
      pending_used_ += k;
      n -= k;
    }
    return ok_status();
  }

 private:
  static Status truncated(const std::string& what) { return invalid_argument(what + " is truncated"); }

  static int sextet(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  }

  // Four base64 characters (blanks between them skipped) into one to three bytes.
  Status decode_quantum(const std::string& what) {
    std::array<char, 4> chars{};
    for (size_t got = 0; got < 4;) {
      if (position_ == source_.size()) return truncated(what);
      const char c = source_[position_++];
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') continue;
      chars[got++] = c;
    }
    const int padding = chars[3] != '=' ? 0 : chars[2] != '=' ? 1 : 2;
    uint32_t bits = 0;
    for (int i = 0; i < 4 - padding; ++i) {
      const int v = sextet(chars[size_t(i)]);
      if (v < 0) return invalid_argument(what + " has a character that is not base64");
      bits |= uint32_t(v) << (18 - 6 * i);
    }
    pending_.clear();
    pending_used_ = 0;
    for (int i = 0; i < 3 - padding; ++i) pending_.push_back(char((bits >> (16 - 8 * i)) & 0xFF));
    return ok_status();
  }

  std::string_view source_;
  bool base64_;
  size_t position_ = 0;
  std::string pending_;  // the current quantum's bytes
  size_t pending_used_ = 0;
};

Result<uint64_t> read_header_word(ByteReader& reader, const VtkXmlArrayEncoding& e, const std::string& what) {
  std::string word;
  const uint64_t size = e.header_64 ? 8 : 4;
  if (reader.most_left() < size) return invalid_argument(what + " is truncated (no binary header)");
  SOIQ_RETURN_IF_ERROR(reader.take(size, word, what));
  return e.header_64 ? load_scalar<uint64_t>(word.data(), e.big_endian)
                     : uint64_t(load_scalar<uint32_t>(word.data(), e.big_endian));
}

Status over_budget(const std::string& declared, uint64_t budget, const std::string& what) {
  return resource_exhausted(what + " declares " + declared +
                            " bytes once decompressed, more than a surface file of this size can hold (at most " +
                            count_text(budget) + " bytes left)");
}

Status spend(uint64_t bytes, uint64_t& budget, const std::string& what) {
  if (bytes > budget) return over_budget(count_text(bytes), budget, what);
  budget -= bytes;
  return ok_status();
}

Result<std::string> decompress_block(std::string_view block, uint64_t size, VtkXmlCompressor compressor,
                                     const std::string& what) {
  if (compressor == VtkXmlCompressor::kZlib) return inflate_bytes(block, size, what);
  std::string out(size, '\0');
  if (compressor == VtkXmlCompressor::kLz4) {
    if (block.size() > uint64_t(std::numeric_limits<int>::max()) || size > uint64_t(std::numeric_limits<int>::max()))
      return invalid_argument(what + " has an LZ4 block over 2 GB");
    const int n = LZ4_decompress_safe(block.data(), out.data(), int(block.size()), int(size));
    if (n < 0 || uint64_t(n) != size) return invalid_argument(what + " has a corrupt LZ4 block");
    return out;
  }
  // LZMA: VTK writes each block as an .xz stream. The decoder's own memory is capped too.
  uint64_t memory_limit = 256ull << 20;
  size_t in_position = 0, out_position = 0;
  const lzma_ret r =
      lzma_stream_buffer_decode(&memory_limit, 0, nullptr, reinterpret_cast<const uint8_t*>(block.data()), &in_position,
                                block.size(), reinterpret_cast<uint8_t*>(out.data()), &out_position, out.size());
  if (r != LZMA_OK || out_position != size || in_position != block.size())
    return invalid_argument(what + " has a corrupt LZMA block");
  return out;
}

// The array's bytes once decoded and decompressed, every declared size checked first.
Result<std::string> binary_bytes(std::string_view source, const VtkXmlArrayEncoding& e, uint64_t& budget,
                                 const std::string& what) {
  ByteReader reader(source, e.base64);
  std::string out;
  if (e.compressor == VtkXmlCompressor::kNone) {
    SOIQ_ASSIGN_OR_RETURN(const uint64_t n, read_header_word(reader, e, what));
    if (n > reader.most_left()) {
      return invalid_argument(what + " claims " + count_text(n) + " bytes but only " + count_text(reader.most_left()) +
                              " follow");
    }
    SOIQ_RETURN_IF_ERROR(spend(n, budget, what));
    out.reserve(n);
    SOIQ_RETURN_IF_ERROR(reader.take(n, out, what));
    return out;
  }
  SOIQ_ASSIGN_OR_RETURN(const uint64_t blocks, read_header_word(reader, e, what));
  SOIQ_ASSIGN_OR_RETURN(const uint64_t block_size, read_header_word(reader, e, what));
  SOIQ_ASSIGN_OR_RETURN(const uint64_t last_size_word, read_header_word(reader, e, what));
  const uint64_t word = e.header_64 ? 8 : 4;
  if (blocks > reader.most_left() / word) {
    return invalid_argument(what + " claims " + count_text(blocks) +
                            " compressed blocks, more than its bytes can list");
  }
  if (blocks == 0) return out;
  if (block_size == 0 || last_size_word > block_size)
    return invalid_argument(what + " has a compression header with impossible block sizes");
  std::vector<uint64_t> compressed(blocks);
  uint64_t compressed_total = 0;
  for (uint64_t& c : compressed) {
    SOIQ_ASSIGN_OR_RETURN(c, read_header_word(reader, e, what));
    if (c > reader.most_left() || compressed_total > reader.most_left() - c)
      return invalid_argument(what + " claims compressed blocks longer than the bytes that follow");
    compressed_total += c;
  }
  if (compressed_total > reader.most_left())
    return invalid_argument(what + " claims compressed blocks longer than the bytes that follow");
  const uint64_t last_size = last_size_word != 0 ? last_size_word : block_size;
  if (blocks - 1 > budget / block_size) {
    return over_budget(count_text(blocks - 1) + " x " + count_text(block_size) + " and more", budget, what);
  }
  SOIQ_RETURN_IF_ERROR(spend((blocks - 1) * block_size + last_size, budget, what));
  out.reserve((blocks - 1) * block_size + last_size);
  for (uint64_t b = 0; b < blocks; ++b) {
    std::string block;
    block.reserve(compressed[b]);
    SOIQ_RETURN_IF_ERROR(reader.take(compressed[b], block, what));
    SOIQ_ASSIGN_OR_RETURN(std::string plain,
                          decompress_block(block, b + 1 == blocks ? last_size : block_size, e.compressor, what));
    out += plain;
  }
  return out;
}

struct TypeInfo {
  size_t size = 0;
  bool real = false;
};

Result<TypeInfo> type_info(const std::string& type, const std::string& what) {
  static const std::array<std::pair<const char*, TypeInfo>, 10> kTypes{{
      {"Int8", {1, false}},
      {"UInt8", {1, false}},
      {"Int16", {2, false}},
      {"UInt16", {2, false}},
      {"Int32", {4, false}},
      {"UInt32", {4, false}},
      {"Int64", {8, false}},
      {"UInt64", {8, false}},
      {"Float32", {4, true}},
      {"Float64", {8, true}},
  }};
  for (const auto& [name, info] : kTypes)
    if (type == name) return info;
  return invalid_argument(what + " has type '" + type + "'; soiq reads Int8 to UInt64, Float32 and Float64");
}

// Calls `f` with a value of the C++ type the DataArray's `type` names (for its type only).
template <typename F>
void with_type(const std::string& type, F&& f) {
  if (type == "Int8")
    f(int8_t{});
  else if (type == "UInt8")
    f(uint8_t{});
  else if (type == "Int16")
    f(int16_t{});
  else if (type == "UInt16")
    f(uint16_t{});
  else if (type == "Int32")
    f(int32_t{});
  else if (type == "UInt32")
    f(uint32_t{});
  else if (type == "Int64")
    f(int64_t{});
  else if (type == "UInt64")
    f(uint64_t{});
  else if (type == "Float32")
    f(float{});
  else
    f(double{});
}

template <typename Out>
Result<std::vector<Out>> decode(std::string_view source, const VtkXmlArrayEncoding& e, uint64_t expected_count,
                                uint64_t& budget, const std::string& what) {
  SOIQ_ASSIGN_OR_RETURN(const TypeInfo info, type_info(e.type, what));
  if (std::is_integral_v<Out> && info.real) return invalid_argument(what + " must hold integers, not " + e.type);
  std::vector<Out> values;
  if (e.ascii) {
    // Each number takes at least two characters with its separator: the vector grows with the
    // text, never with a count the file states.
    size_t i = 0;
    while (true) {
      i = source.find_first_not_of(" \t\r\n", i);
      if (i == std::string_view::npos) break;
      size_t end = source.find_first_of(" \t\r\n", i);
      if (end == std::string_view::npos) end = source.size();
      const std::string_view token = source.substr(i, end - i);
      Out v{};
      const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
      if (ec != std::errc() || ptr != token.data() + token.size() || (info.real && !std::isfinite(double(v))))
        return invalid_argument(what + " has '" + std::string(token.substr(0, 32)) + "', not a finite number");
      if (values.size() == expected_count)
        return invalid_argument(what + " holds more than the " + count_text(expected_count) + " values expected");
      values.push_back(v);
      i = end;
    }
  } else {
    SOIQ_ASSIGN_OR_RETURN(const std::string raw, binary_bytes(source, e, budget, what));
    if (raw.size() % info.size != 0 || raw.size() / info.size != expected_count) {
      return invalid_argument(what + " holds " + count_text(raw.size() / info.size) + " values where " +
                              count_text(expected_count) + " are expected");
    }
    values.reserve(expected_count);
    Status status = ok_status();
    with_type(e.type, [&](auto zero) {
      using T = decltype(zero);
      for (size_t k = 0; k < raw.size() && status.ok(); k += sizeof(T)) {
        const T v = load_scalar<T>(raw.data() + k, e.big_endian);
        if constexpr (std::is_floating_point_v<T>) {
          if (!std::isfinite(v)) status = invalid_argument(what + " holds a value that is not finite");
        } else if constexpr (std::is_same_v<T, uint64_t>) {
          if (v > uint64_t(std::numeric_limits<int64_t>::max()))
            status = invalid_argument(what + " holds a value above 2^63-1");
        }
        values.push_back(Out(v));
      }
    });
    SOIQ_RETURN_IF_ERROR(status);
  }
  if (values.size() != expected_count) {
    return invalid_argument(what + " holds " + count_text(values.size()) + " values where " +
                            count_text(expected_count) + " are expected");
  }
  return values;
}

}  // namespace

Result<std::vector<double>> decode_vtk_xml_reals(std::string_view source, const VtkXmlArrayEncoding& encoding,
                                                 uint64_t expected_count, uint64_t& budget, const std::string& what) {
  return decode<double>(source, encoding, expected_count, budget, what);
}

Result<std::vector<int64_t>> decode_vtk_xml_integers(std::string_view source, const VtkXmlArrayEncoding& encoding,
                                                     uint64_t expected_count, uint64_t& budget,
                                                     const std::string& what) {
  return decode<int64_t>(source, encoding, expected_count, budget, what);
}

}  // namespace soiq
