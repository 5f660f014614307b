#include "core/io/parse_ply.h"

#include <cstdint>
#include <limits>
#include <vector>

#include "core/io/mesh_text.h"
#include "core/io/ply_header.h"

namespace soiq {
namespace ply {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr TypeInfo kTypes[] = {
    {"char", Type::kInt8, 1, -128, 127},
    {"int8", Type::kInt8, 1, -128, 127},
    {"uchar", Type::kUint8, 1, 0, 255},
    {"uint8", Type::kUint8, 1, 0, 255},
    {"short", Type::kInt16, 2, -32768, 32767},
    {"int16", Type::kInt16, 2, -32768, 32767},
    {"ushort", Type::kUint16, 2, 0, 65535},
    {"uint16", Type::kUint16, 2, 0, 65535},
    {"int", Type::kInt32, 4, -2147483648.0, 2147483647.0},
    {"int32", Type::kInt32, 4, -2147483648.0, 2147483647.0},
    {"uint", Type::kUint32, 4, 0, 4294967295.0},
    {"uint32", Type::kUint32, 4, 0, 4294967295.0},
    {"float", Type::kFloat32, 4, -kInf, kInf},
    {"float32", Type::kFloat32, 4, -kInf, kInf},
    {"double", Type::kFloat64, 8, -kInf, kInf},
    {"float64", Type::kFloat64, 8, -kInf, kInf},
};

const TypeInfo* type_named(std::string_view name) {
  for (const TypeInfo& t : kTypes) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

// Names go into messages: they must be printable and short (quoted() shows them unchanged).
bool is_short_word(std::string_view s) { return quoted(s) == "'" + std::string(s) + "'"; }

Status bad_header(const std::string& name, int64_t line, const std::string& why) {
  return invalid_argument(line_where("PLY", name, line) + ": " + why);
}

// Marks x, y, z of `vertex` and the corner list of `face`; checks that they are there and usable.
Status assign_roles(Header& h, const std::string& name) {
  Element* vertex = nullptr;
  for (Element& e : h.elements) {
    for (const Element& other : h.elements) {
      if (&other != &e && other.name == e.name) {
        return invalid_argument("PLY '" + name + "' declares element '" + e.name + "' twice");
      }
    }
    if (e.name == "tristrips") {
      return invalid_argument("PLY '" + name + "' has triangle strips ('tristrips'), which soiq does not read");
    }
    if (e.name == "vertex") {
      vertex = &e;
      for (Property& p : e.properties) {
        if (p.count != nullptr || (p.name != "x" && p.name != "y" && p.name != "z")) continue;
        p.role = p.name == "x" ? Role::kX : p.name == "y" ? Role::kY : Role::kZ;
      }
    }
    if (e.name == "face") {
      int lists = 0;
      for (Property& p : e.properties) {
        if (p.count == nullptr || (p.name != "vertex_indices" && p.name != "vertex_index")) continue;
        if (!is_integer(*p.type)) {
          return invalid_argument("PLY '" + name + "': face list '" + p.name + "' must hold integers, not " +
                                  std::string(p.type->name));
        }
        p.role = Role::kCorners;
        ++lists;
      }
      if (lists != 1) {
        return invalid_argument("PLY '" + name + "': element 'face' needs one 'vertex_indices' list, it has " +
                                std::to_string(lists));
      }
    }
  }
  if (vertex == nullptr) return invalid_argument("PLY '" + name + "' has no 'vertex' element");
  for (const char* axis : {"x", "y", "z"}) {
    int scalars = 0, named = 0;
    for (const Property& p : vertex->properties) {
      named += p.name == axis;
      scalars += p.name == axis && p.count == nullptr;
    }
    if (named != 1 || scalars != 1) {
      return invalid_argument("PLY '" + name + "': element 'vertex' needs one scalar property '" + axis + "'");
    }
  }
  h.vertices = vertex->count;
  return ok_status();
}

Result<Header> parse_header(std::string_view bytes, const std::string& name) {
  Header h;
  LineReader lines(bytes);
  std::string_view line;
  std::vector<std::string_view> w;
  if (!lines.next(line) || line != "ply") {
    return invalid_argument("PLY '" + name + "' does not start with the line 'ply'");
  }
  bool format_seen = false;
  while (true) {
    if (!lines.next(line)) return invalid_argument("PLY '" + name + "' has no 'end_header' line (truncated header?)");
    const int64_t n = lines.line_number();
    words_of(line, w);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header" && w.size() == 1) break;
    if (w[0] == "format") {
      if (format_seen || w.size() != 3 || w[2] != "1.0")
        return bad_header(name, n, "expected 'format <type> 1.0' once");
      if (w[1] == "ascii") {
        h.format = Format::kAscii;
      } else if (w[1] == "binary_little_endian") {
        h.format = Format::kLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        h.format = Format::kBigEndian;
      } else {
        return bad_header(name, n, "unknown format " + quoted(w[1]));
      }
      format_seen = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) return bad_header(name, n, "expected 'element <name> <count>'");
      SOIQ_ASSIGN_OR_RETURN(const int64_t count, whole_integer(w[2], line_where("PLY", name, n)));
      if (count < 0) return bad_header(name, n, "negative element count " + std::to_string(count));
      if (!is_short_word(w[1]))
        return bad_header(name, n, "element name " + quoted(w[1]) + " is not a short printable word");
      h.elements.push_back({std::string(w[1]), uint64_t(count), {}, false});
    } else if (w[0] == "property") {
      if (h.elements.empty()) return bad_header(name, n, "'property' before any 'element'");
      Element& e = h.elements.back();
      const std::string_view property_name = w.back();
      if (!is_short_word(property_name)) {
        return bad_header(name, n, "property name " + quoted(property_name) + " is not a short printable word");
      }
      if (w.size() == 3 && type_named(w[1]) != nullptr) {
        e.properties.push_back({std::string(w[2]), type_named(w[1])});
      } else if (w.size() == 5 && w[1] == "list" && type_named(w[2]) != nullptr && type_named(w[3]) != nullptr) {
        if (!is_integer(*type_named(w[2]))) return bad_header(name, n, "a list count must have an integer type");
        e.properties.push_back({std::string(w[4]), type_named(w[3]), type_named(w[2])});
        e.has_list = true;
      } else {
        return bad_header(name, n, "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
    } else {
      return bad_header(name, n, "unknown header keyword " + quoted(w[0]));
    }
  }
  if (!format_seen) return invalid_argument("PLY '" + name + "' has no 'format' line");
  h.body_offset = lines.offset();
  h.lines = lines.line_number();
  SOIQ_RETURN_IF_ERROR(assign_roles(h, name));
  return h;
}

// Every element instance takes at least a few bytes (ASCII: a digit and a separator per
// property; binary: each scalar and each list count): a count the remaining bytes cannot hold is
// refused here, before anything is allocated for it.
Status check_counts(const Header& h, size_t body_bytes, const std::string& name) {
  uint64_t remaining = body_bytes + 1;  // ASCII: the last line may lack its newline
  for (const Element& e : h.elements) {
    if (e.count == 0) continue;
    if (e.properties.empty()) {
      return invalid_argument("PLY '" + name + "': element '" + e.name + "' has " + std::to_string(e.count) +
                              " items but no properties");
    }
    uint64_t least = 0;
    for (const Property& p : e.properties) {
      least += h.format == Format::kAscii ? 2 : uint64_t(p.count != nullptr ? p.count->size : p.type->size);
    }
    if (e.count > remaining / least) {
      return invalid_argument("PLY '" + name + "' is truncated or corrupt: element '" + e.name + "' announces " +
                              std::to_string(e.count) + " items of at least " + std::to_string(least) +
                              " bytes, but the data has " + std::to_string(body_bytes) + " bytes");
    }
    remaining -= e.count * least;
  }
  if (h.vertices > uint64_t(std::numeric_limits<int32_t>::max())) {
    return resource_exhausted("PLY '" + name + "' has more than 2^31 vertices");
  }
  return ok_status();
}

}  // namespace
}  // namespace ply

Result<TriangleMesh> parse_ply(std::string_view bytes, const std::string& name) {
  SOIQ_ASSIGN_OR_RETURN(const ply::Header h, ply::parse_header(bytes, name));
  const std::string_view body = bytes.substr(h.body_offset);
  SOIQ_RETURN_IF_ERROR(ply::check_counts(h, body.size(), name));
  TriangleMesh mesh;
  mesh.vertices_mm.reserve(size_t(h.vertices));
  for (const ply::Element& e : h.elements) {
    if (e.name == "face") mesh.triangles.reserve(size_t(e.count));
  }
  if (h.format == ply::Format::kAscii) {
    SOIQ_RETURN_IF_ERROR(ply::parse_ascii_body(h, body, name, mesh));
  } else {
    SOIQ_RETURN_IF_ERROR(ply::parse_binary_body(h, body, name, mesh));
  }
  return mesh;
}

}  // namespace soiq
