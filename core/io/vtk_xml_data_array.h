#pragma once
// Decodes the values of one DataArray of a VTK XML file (.vtp) from the file's bytes, checking
// every size the file states against the bytes there are before anything is allocated. VTK 9.1's
// own reader allocates whatever a binary header or an offsets array claims (1 KB of .vtp asked it
// for 768 GB), so soiq reads the arrays itself and VTK only parses the XML around them.
//
// The encodings (VTK's "VTK File Formats", XML section): `format="ascii"` (numbers separated by
// blanks), `format="binary"` (base64 inline) and `format="appended"` (at `offset` in the
// AppendedData section, raw or base64). Binary data starts with a header of UInt32 or UInt64 words
// (`header_type`): uncompressed, one word giving the byte count; compressed (`compressor` zlib,
// LZ4 or LZMA), the block count, the block size, the last block's size (0: a full block) and each
// block's compressed size, then the blocks.
//
// Inputs   `source` where the array's data starts (the element's text, or the appended section
//          from the array's offset on); `expected_count` values the caller needs (the count is
//          compared, never used to allocate); `budget` bytes the whole file may still inflate to,
//          decreased by what this array declares (compressed data may expand, so a file's decoded
//          size is bounded by a multiple of its own size rather than by what its headers say).
// Output   the values widened to double (any numeric type; NaN and infinities refused) or int64
//          (integer types only; a UInt64 above 2^63-1 refused).
// Errors   INVALID_ARGUMENT naming `what` ("mesh 'name': DataArray 'offsets'"): bad base64,
//          truncated data, a header claiming more bytes than follow, a block that does not
//          decompress to its stated size, a count other than `expected_count`, an unknown type or
//          compressor; RESOURCE_EXHAUSTED when the declared sizes exceed `budget`.
// Cost     O(bytes of the array + its decoded size); thread-safe.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"

namespace soiq {

enum class VtkXmlCompressor { kNone, kZlib, kLz4, kLzma };

struct VtkXmlArrayEncoding {
  std::string type;        // the DataArray's `type`: Int8 ... UInt64, Float32, Float64
  bool ascii = false;      // format="ascii": `source` is the element's text
  bool base64 = true;      // binary inline, or appended with encoding="base64"; false: appended raw
  bool header_64 = false;  // header_type="UInt64"
  bool big_endian = false;
  VtkXmlCompressor compressor = VtkXmlCompressor::kNone;
};

Result<std::vector<double>> decode_vtk_xml_reals(std::string_view source, const VtkXmlArrayEncoding& encoding,
                                                 uint64_t expected_count, uint64_t& budget, const std::string& what);

Result<std::vector<int64_t>> decode_vtk_xml_integers(std::string_view source, const VtkXmlArrayEncoding& encoding,
                                                     uint64_t expected_count, uint64_t& budget,
                                                     const std::string& what);

}  // namespace soiq
