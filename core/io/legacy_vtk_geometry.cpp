#include "core/io/legacy_vtk_geometry.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/io/header_text.h"

namespace soiq {
namespace {

int scalar_size(const std::string& type) {
  if (type == "char" || type == "unsigned_char" || type == "bit") return 1;
  if (type == "short" || type == "unsigned_short") return 2;
  if (type == "int" || type == "unsigned_int" || type == "float" || type == "vtktypeint32") return 4;
  if (type == "long" || type == "unsigned_long" || type == "double" || type == "vtktypeint64" || type == "vtkIdType" ||
      type == "vtktypeuint64")
    return 8;
  return 0;
}

// Reads the legacy format: lines of keywords, then ASCII tokens or big-endian binary blocks.
class Scanner {
 public:
  Scanner(const std::string& bytes, bool binary) : s_(bytes), binary_(binary) {}

  size_t pos() const { return pos_; }
  void set_pos(size_t p) { pos_ = p; }
  bool at_end() {
    skip_space();
    return pos_ >= s_.size();
  }
  // The next non-blank line's words (pos_ moves past it).
  std::vector<std::string> line_words() {
    skip_space();
    const size_t end = s_.find('\n', pos_);
    const std::string_view line = std::string_view(s_).substr(pos_, end == std::string::npos ? s_.npos : end - pos_);
    pos_ = end == std::string::npos ? s_.size() : end + 1;
    std::vector<std::string> words;
    for (const auto w : split_words(line)) words.emplace_back(w);
    return words;
  }
  // `count` values of `size` bytes (binary) or `count` numeric tokens (ASCII); integers go to `out`
  // when it is not null. False when the data ends early or a token is not a number.
  bool values(int64_t count, int size, bool integer, std::vector<int64_t>* out) {
    if (count < 0) return false;
    if (binary_) {
      if (pos_ < s_.size() && s_[pos_] == '\n') ++pos_;
      if (int64_t(s_.size() - pos_) / size < count) return false;
      for (int64_t n = 0; n < count && out; ++n) {
        uint64_t v = 0;
        for (int b = 0; b < size; ++b) v = (v << 8) | uint8_t(s_[pos_ + size_t(n * size + b)]);
        // Sign-extend: ids are signed in every supported type.
        const int bits = 8 * size;
        const int64_t sv = bits == 64 ? int64_t(v) : (v >> (bits - 1)) ? int64_t(v) - (int64_t(1) << bits) : int64_t(v);
        out->push_back(sv);
      }
      pos_ += size_t(count * size);
      return true;
    }
    for (int64_t n = 0; n < count; ++n) {
      skip_space();
      const size_t start = pos_;
      while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      const std::string_view token = std::string_view(s_).substr(start, pos_ - start);
      if (token.empty()) return false;
      if (integer || out) {
        const auto v = parse_integer(token);
        if (!v) return false;
        if (out) out->push_back(*v);
      } else if (!parse_double(token)) {
        return false;
      }
    }
    return true;
  }

 private:
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  const std::string& s_;
  bool binary_;
  size_t pos_ = 0;
};

Status bad(const std::string& path, const std::string& why) {
  return invalid_argument("legacy VTK '" + path + "': " + why);
}

struct LegacyHeader {
  double version = 0;
  bool binary = false;
  size_t body_start = 0;  // first byte after the third line
};

// The three header lines: the version decides how cell sections are laid out (counts before 5.0,
// OFFSETS and CONNECTIVITY since), the third line how values are stored (ASCII or BINARY).
Result<LegacyHeader> read_header(const std::string& bytes, const std::string& path) {
  const size_t l1 = bytes.find('\n');
  const size_t l2 = l1 == std::string::npos ? l1 : bytes.find('\n', l1 + 1);
  const size_t l3 = l2 == std::string::npos ? l2 : bytes.find('\n', l2 + 1);
  if (!bytes.starts_with("# vtk DataFile Version") || l3 == std::string::npos) return bad(path, "malformed header");
  const std::string_view version_text = trim(std::string_view(bytes).substr(22, l1 - 22));
  // Only the versions VTK writes: VTK parses others its own way ("501" crashed its reader), so this
  // check could not know which layout VTK would read.
  static constexpr std::string_view kVersions[] = {"1.0", "2.0", "3.0", "4.0", "4.1", "4.2", "5.0", "5.1"};
  if (std::find(std::begin(kVersions), std::end(kVersions), version_text) == std::end(kVersions))
    return bad(path,
               "unsupported file version '" + std::string(version_text.substr(0, 20)) + "' (soiq reads 1.0 to 5.1)");
  const auto version = parse_double(version_text);
  if (!version) return bad(path, "malformed header version");
  const std::string format = std::string(trim(std::string_view(bytes).substr(l2 + 1, l3 - l2 - 1)));
  if (format != "ASCII" && format != "BINARY") return bad(path, "third line must be ASCII or BINARY");
  return LegacyHeader{*version, format == "BINARY", l3 + 1};
}

// A cell section before 5.0: `size` ints, per cell its point count and its point ids. Checks that
// the counts of `cells` cells add up to `size` and every id is one of the `points` points, since
// VTK's reader trusts both.
Status check_counted_cells(Scanner& in, const std::string& key, int64_t cells, int64_t size, int64_t points,
                           const std::string& path) {
  std::vector<int64_t> ids;
  if (!in.values(size, 4, true, &ids)) return bad(path, key + " data is truncated or malformed");
  size_t k = 0;
  for (int64_t cell = 0; cell < cells; ++cell) {
    if (k >= ids.size() || ids[k] < 0 || int64_t(ids.size() - k - 1) < ids[k])
      return bad(path, key + " counts do not add up");
    const int64_t npts = ids[k++];
    for (int64_t m = 0; m < npts; ++m, ++k) {
      if (ids[k] < 0 || ids[k] >= points)
        return bad(path, key + " point index " + std::to_string(ids[k]) + " is out of range");
    }
  }
  if (k != ids.size()) return bad(path, key + " counts do not add up");
  return ok_status();
}

// A cell section since 5.0: OFFSETS (`offset_count` values) then CONNECTIVITY (`size` values).
// Checks that the offsets rise to `size` and every id is one of the `points` points, since VTK's
// reader trusts both.
Status check_offset_cells(Scanner& in, const std::string& key, int64_t offset_count, int64_t size, int64_t points,
                          const std::string& path) {
  std::vector<int64_t> offsets, ids;
  const auto off = in.line_words();
  if (off.size() != 2 || off[0] != "OFFSETS" || scalar_size(off[1]) == 0) return bad(path, key + " without OFFSETS");
  if (!in.values(offset_count, scalar_size(off[1]), true, &offsets))
    return bad(path, key + " OFFSETS are truncated or malformed");
  const auto conn = in.line_words();
  if (conn.size() != 2 || conn[0] != "CONNECTIVITY" || scalar_size(conn[1]) == 0)
    return bad(path, key + " without CONNECTIVITY");
  if (!in.values(size, scalar_size(conn[1]), true, &ids))
    return bad(path, key + " CONNECTIVITY is truncated or malformed");
  for (size_t k = 0; k < offsets.size(); ++k) {
    if (offsets[k] < 0 || offsets[k] > size || (k > 0 && offsets[k] < offsets[k - 1]))
      return bad(path, key + " OFFSETS are not increasing");
  }
  if (!offsets.empty() && offsets.back() != size)
    return bad(path, key + " OFFSETS do not end at the CONNECTIVITY size");
  for (const int64_t id : ids) {
    if (id < 0 || id >= points) return bad(path, key + " point index " + std::to_string(id) + " is out of range");
  }
  return ok_status();
}

// A VERTICES, LINES, POLYGONS or TRIANGLE_STRIPS section whose keyword line is `w`: its two counts,
// then its data in the layout of the file's version.
Status check_cell_section(Scanner& in, const std::vector<std::string>& w, double version, int64_t points,
                          const std::string& path) {
  const std::string& key = w[0];
  const auto a = w.size() == 3 ? parse_integer(w[1]) : std::nullopt;
  const auto b = w.size() == 3 ? parse_integer(w[2]) : std::nullopt;
  if (!a || !b || *a < 0 || *b < 0) return bad(path, "malformed " + key + " line");
  if (version < 5.0) return check_counted_cells(in, key, *a, *b, points, path);
  return check_offset_cells(in, key, *a, *b, points, path);
}

}  // namespace

Result<std::string> legacy_vtk_geometry(const std::string& bytes, const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const LegacyHeader header, read_header(bytes, path));
  Scanner in(bytes, header.binary);
  in.set_pos(header.body_start);
  const auto dataset = in.line_words();
  if (dataset.size() != 2 || dataset[0] != "DATASET" || dataset[1] != "POLYDATA") {
    return bad(path, "not polydata (expected 'DATASET POLYDATA')");
  }
  int64_t points = -1;
  // What VTK's reader gets: the checked sections, without METADATA blocks (VTK would read their
  // contents by its own rules, which could differ from where this check thinks a block ends).
  std::string geometry;
  size_t kept_from = 0;
  while (!in.at_end()) {
    const size_t section_start = in.pos();
    const auto w = in.line_words();
    if (w.empty()) continue;
    const std::string& key = w[0];
    if (key == "POINT_DATA" || key == "CELL_DATA" || key == "FIELD") {
      geometry += bytes.substr(kept_from, section_start - kept_from);
      kept_from = bytes.size();
      break;
    }
    if (key == "METADATA") {
      // Key/value information up to a blank line: dropped.
      const size_t blank = bytes.find("\n\n", in.pos());
      if (blank == std::string::npos) return bad(path, "METADATA is not ended by a blank line");
      geometry += bytes.substr(kept_from, section_start - kept_from);
      kept_from = blank + 2;
      in.set_pos(kept_from);
      continue;
    }
    if (key == "POINTS") {
      const auto n = w.size() == 3 ? parse_integer(w[1]) : std::nullopt;
      const int size = w.size() == 3 ? scalar_size(w[2]) : 0;
      if (!n || *n < 0 || size == 0) return bad(path, "malformed POINTS line");
      // Every coordinate takes at least a byte, so a count past a third of the file cannot be met
      // (and 3 * count must not overflow).
      if (*n > int64_t(bytes.size() / 3)) return bad(path, "POINTS data is truncated or malformed");
      if (!in.values(3 * *n, size, false, nullptr)) return bad(path, "POINTS data is truncated or malformed");
      points = *n;
      continue;
    }
    if (key != "VERTICES" && key != "LINES" && key != "POLYGONS" && key != "TRIANGLE_STRIPS") {
      return bad(path, "unsupported section '" + key.substr(0, 40) + "'");
    }
    if (points < 0) return bad(path, key + " before POINTS");
    SOIQ_RETURN_IF_ERROR(check_cell_section(in, w, header.version, points, path));
  }
  if (points < 0) return bad(path, "no POINTS section");
  geometry += bytes.substr(std::min(kept_from, bytes.size()));
  return geometry;
}

}  // namespace soiq
