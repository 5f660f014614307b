#pragma once
// Internal to core/io/parse_ply.cpp and ply_body.cpp, not part of parse_ply's interface
// (parse_ply.h): a PLY header as parse_ply.cpp reads and checks it, and the readers of the body it
// describes (ply_body.cpp), one for ASCII and one for both binary byte orders.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq::ply {

// A scalar type of the PLY format; TypeInfo gives each of its two names ("uchar", "uint8").
enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct TypeInfo {
  std::string_view name;
  Type type;
  int size;
  double min, max;  // the integer range; +-inf for floats
};

inline bool is_integer(const TypeInfo& t) { return t.type != Type::kFloat32 && t.type != Type::kFloat64; }

// What parse_ply keeps of a property: a vertex coordinate, a face's corner list, or nothing.
enum class Role { kSkip, kX, kY, kZ, kCorners };

// A `property` line: a scalar, or a list with the type of its count and of its items.
struct Property {
  std::string name;
  const TypeInfo* type;             // of the scalar, or of each list item
  const TypeInfo* count = nullptr;  // of the list count; null for a scalar
  Role role = Role::kSkip;
};

// An `element` line and its properties; has_list when one of them is a list.
struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  bool has_list = false;
};

// The `format` line: how the body stores values.
enum class Format { kAscii, kLittleEndian, kBigEndian };

// The header as parse_ply.cpp reads and checks it, with the roles assigned and vertices = the
// vertex element's count.
struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  size_t body_offset = 0;  // first byte after the end_header line
  int64_t lines = 0;       // lines in the header
  uint64_t vertices = 0;
};

// ply_body.cpp: the elements `h` declares, read from `body` (the bytes after the header; element
// counts already checked against its size) into `mesh`: vertices and triangles as parse_ply.h says.
// `name` names the file in messages.
Status parse_ascii_body(const Header& h, std::string_view body, const std::string& name, TriangleMesh& mesh);
Status parse_binary_body(const Header& h, std::string_view body, const std::string& name, TriangleMesh& mesh);

}  // namespace soiq::ply
