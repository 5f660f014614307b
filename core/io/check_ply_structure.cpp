#include "core/io/check_ply_structure.h"

#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include "core/io/header_text.h"

namespace soiq {
namespace {

struct Property {
  std::string name;
  int size = 0;        // bytes of a scalar, or of each list item
  int count_size = 0;  // > 0 for a list: bytes of its count
  bool item_signed = false;
  bool item_float = false;
};

struct Element {
  std::string name;
  int64_t count = 0;
  std::vector<Property> properties;
};

int type_size(std::string_view type) {
  static const std::map<std::string_view, int> kSizes = {{"char", 1},  {"int8", 1},    {"uchar", 1},  {"uint8", 1},
                                                         {"short", 2}, {"int16", 2},   {"ushort", 2}, {"uint16", 2},
                                                         {"int", 4},   {"int32", 4},   {"uint", 4},   {"uint32", 4},
                                                         {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = kSizes.find(type);
  return it == kSizes.end() ? 0 : it->second;
}

Status bad(const std::string& path, const std::string& why) {
  return invalid_argument("PLY '" + path + "' is malformed: " + why);
}

// An unsigned list count of `size` bytes in the file's byte order; -1 for a negative signed count.
int64_t read_count(const char* p, int size, bool big_endian) {
  uint64_t value = 0;
  for (int b = 0; b < size; ++b) {
    const int shift = 8 * (big_endian ? size - 1 - b : b);
    value |= uint64_t(uint8_t(p[b])) << shift;
  }
  return int64_t(value);  // counts are at most 32 bits: never negative here
}

// A list item as a vertex index; nullopt when it is not an integer.
std::optional<int64_t> read_index(const char* p, const Property& prop, bool big_endian) {
  if (prop.item_float) return std::nullopt;
  const int64_t raw = read_count(p, prop.size, big_endian);
  if (!prop.item_signed) return raw;
  const int bits = 8 * prop.size;
  return bits == 64 ? raw : (raw >= (int64_t(1) << (bits - 1)) ? raw - (int64_t(1) << bits) : raw);
}

bool is_face_index_list(const Element& e, const Property& p) {
  return e.name == "face" && p.count_size > 0 && (p.name == "vertex_indices" || p.name == "vertex_index");
}

}  // namespace

Status check_ply_structure(const std::string& bytes, const std::string& path) {
  const size_t end = bytes.find("end_header");
  if (!bytes.starts_with("ply") || end == std::string::npos) {
    return bad(path, "no 'ply' magic or no 'end_header' (truncated header?)");
  }
  const size_t body = bytes.find('\n', end);
  if (body == std::string::npos) return bad(path, "truncated after 'end_header'");
  std::vector<Element> elements;
  std::string format;
  size_t start = bytes.find('\n') + 1;
  while (start < end) {
    size_t stop = bytes.find('\n', start);
    const auto words = split_words(std::string_view(bytes).substr(start, stop - start));
    start = stop + 1;
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "format") {
      if (words.size() != 3 || words[2] != "1.0") return bad(path, "bad format line");
      format = std::string(words[1]);
    } else if (words[0] == "element") {
      const auto n = words.size() == 3 ? parse_integer(words[2]) : std::nullopt;
      if (!n || *n < 0) return bad(path, "bad element line");
      elements.push_back({std::string(words[1]), *n, {}});
    } else if (words[0] == "property") {
      if (elements.empty()) return bad(path, "property before any element");
      if (words.size() == 3 && type_size(words[1]) > 0) {
        elements.back().properties.push_back({std::string(words[2]), type_size(words[1]), 0});
      } else if (words.size() == 5 && words[1] == "list" && type_size(words[2]) > 0 && type_size(words[3]) > 0 &&
                 type_size(words[2]) <= 4) {
        const bool is_float = words[3].starts_with("float") || words[3] == "double";
        const bool is_signed = words[3] == "char" || words[3] == "short" || words[3] == "int" ||
                               (words[3].starts_with("int") && !is_float);
        elements.back().properties.push_back(
            {std::string(words[4]), type_size(words[3]), type_size(words[2]), is_signed, is_float});
      } else {
        return bad(path, "bad property line");
      }
    } else if (words[0] != "end_header") {
      return bad(path, "unknown header keyword '" + std::string(words[0]) + "'");
    }
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian") {
    return bad(path, "missing or unknown format");
  }
  bool has_xyz = false;
  int64_t vertex_count = 0;
  for (const Element& e : elements) {
    if (e.name != "vertex") continue;
    vertex_count = e.count;
    int found = 0;
    for (const Property& p : e.properties) found += (p.name == "x" || p.name == "y" || p.name == "z") && !p.count_size;
    has_xyz = found == 3;
  }
  if (!has_xyz) return bad(path, "no 'vertex' element with x, y and z properties");

  const std::string_view data = std::string_view(bytes).substr(body + 1);
  if (format == "ascii") {
    const auto words = split_words(data);
    size_t w = 0;
    for (const Element& e : elements) {
      for (int64_t n = 0; n < e.count; ++n) {
        for (const Property& p : e.properties) {
          if (w >= words.size()) return bad(path, "truncated in element '" + e.name + "'");
          if (!parse_double(words[w])) return bad(path, "non-numeric value '" + std::string(words[w]) + "'");
          int64_t items = 0;
          if (p.count_size) {
            const auto count = parse_integer(words[w]);
            if (!count || *count < 0) return bad(path, "bad list count in element '" + e.name + "'");
            items = *count;
          }
          ++w;
          if (int64_t(words.size() - w) < items) return bad(path, "truncated in element '" + e.name + "'");
          for (int64_t k = 0; k < items; ++k, ++w) {
            if (!is_face_index_list(e, p)) continue;
            const auto index = parse_integer(words[w]);
            if (!index || *index < 0 || *index >= vertex_count) {
              return bad(path, "face index '" + std::string(words[w]) + "' is out of range (" +
                                   std::to_string(vertex_count) + " vertices)");
            }
          }
        }
      }
    }
    return ok_status();
  }
  const bool big_endian = format == "binary_big_endian";
  size_t pos = 0;
  for (const Element& e : elements) {
    // Every instance of an element with properties takes at least one byte: bound the loop.
    if (!e.properties.empty() && e.count > int64_t(data.size())) {
      return bad(path, "truncated: element '" + e.name + "' announces " + std::to_string(e.count) + " items");
    }
    for (int64_t n = 0; n < e.count; ++n) {
      for (const Property& p : e.properties) {
        int64_t items = 1;
        if (p.count_size) {
          if (data.size() - pos < size_t(p.count_size)) return bad(path, "truncated in element '" + e.name + "'");
          items = read_count(data.data() + pos, p.count_size, big_endian);
          pos += size_t(p.count_size);
        }
        if (int64_t(data.size() - pos) < items * p.size) return bad(path, "truncated in element '" + e.name + "'");
        for (int64_t k = 0; k < items; ++k, pos += size_t(p.size)) {
          if (!is_face_index_list(e, p)) continue;
          const auto index = read_index(data.data() + pos, p, big_endian);
          if (!index || *index < 0 || *index >= vertex_count) {
            return bad(path, "face index " + (index ? std::to_string(*index) : std::string("(not an integer)")) +
                                 " is out of range (" + std::to_string(vertex_count) + " vertices)");
          }
        }
      }
    }
  }
  return ok_status();
}

}  // namespace soiq
