// The body of a PLY file, read as its header (ply_header.h) declares it: one element instance per
// line in ASCII, or packed scalars in either byte order in binary. Each instance's coordinates and
// face corners go to the mesh; every other value is read past by its type.

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/io/byte_order.h"
#include "core/io/mesh_text.h"
#include "core/io/ply_header.h"

namespace soiq::ply {
namespace {

// Collects one element instance's values into the mesh.
struct Sink {
  TriangleMesh& mesh;
  uint64_t vertices;
  std::vector<int64_t> corners;
  Vec3 p{};

  void coordinate(Role role, double v) { p[int(role) - int(Role::kX)] = v; }

  // Fans the corners read into triangles; `where()` names the face, built only for a message.
  template <typename Where>
  Status add_face(const Where& where) {
    if (corners.size() < 3) {
      return invalid_argument(where() + ": face has " + std::to_string(corners.size()) +
                              " corners; a face needs at least 3");
    }
    for (const int64_t c : corners) {
      if (c < 0 || uint64_t(c) >= vertices) {
        return invalid_argument(where() + ": face index " + std::to_string(c) + " is out of range (" +
                                std::to_string(vertices) + " vertices)");
      }
    }
    for (size_t k = 1; k + 1 < corners.size(); ++k) {
      mesh.triangles.push_back({int32_t(corners[0]), int32_t(corners[k]), int32_t(corners[k + 1])});
    }
    return ok_status();
  }
};

// One ASCII value of type `t`; coordinates must be finite, skipped floats may be NaN.
Result<double> ascii_value(std::string_view token, const TypeInfo& t, bool coordinate, const std::string& where) {
  if (!is_integer(t)) return coordinate ? finite_number(token, where) : any_number(token, where);
  SOIQ_ASSIGN_OR_RETURN(const int64_t v, whole_integer(token, where));
  if (double(v) < t.min || double(v) > t.max) {
    return invalid_argument(where + ": " + std::to_string(v) + " is out of range for " + std::string(t.name));
  }
  return double(v);
}

double binary_value(const char* p, Type t, bool big) {
  switch (t) {
    case Type::kInt8:
      return double(load_scalar<int8_t>(p, big));
    case Type::kUint8:
      return double(load_scalar<uint8_t>(p, big));
    case Type::kInt16:
      return double(load_scalar<int16_t>(p, big));
    case Type::kUint16:
      return double(load_scalar<uint16_t>(p, big));
    case Type::kInt32:
      return double(load_scalar<int32_t>(p, big));
    case Type::kUint32:
      return double(load_scalar<uint32_t>(p, big));
    case Type::kFloat32:
      return double(load_scalar<float>(p, big));
    case Type::kFloat64:
      return load_scalar<double>(p, big);
  }
  return 0;
}

}  // namespace

Status parse_ascii_body(const Header& h, std::string_view body, const std::string& name, TriangleMesh& mesh) {
  LineReader lines(body, h.lines + 1);
  Sink sink{mesh, h.vertices, {}};
  std::vector<std::string_view> words;
  std::string_view line;
  for (const Element& e : h.elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    for (uint64_t item = 0; item < e.count; ++item) {
      do {
        if (!lines.next(line)) {
          return invalid_argument("PLY '" + name + "' ends in element '" + e.name + "' after " + std::to_string(item) +
                                  " of " + std::to_string(e.count) + " items; is it truncated?");
        }
        words_of(line, words);
      } while (words.empty());
      const std::string where = line_where("PLY", name, lines.line_number());
      // Values the header (and the list counts read so far) declare for this line.
      size_t declared = e.properties.size();
      const auto count_mismatch = [&] {
        return invalid_argument(where + ": " + e.name + " has " + std::to_string(words.size()) +
                                " values, the header " + (e.has_list ? "and its list counts declare " : "declares ") +
                                std::to_string(declared));
      };
      size_t w = 0;
      sink.corners.clear();
      for (const Property& p : e.properties) {
        if (w >= words.size()) return count_mismatch();
        if (p.count == nullptr) {
          SOIQ_ASSIGN_OR_RETURN(const double v, ascii_value(words[w++], *p.type, p.role != Role::kSkip, where));
          if (p.role != Role::kSkip) sink.coordinate(p.role, v);
          continue;
        }
        SOIQ_ASSIGN_OR_RETURN(const double items, ascii_value(words[w++], *p.count, false, where));
        if (items < 0) return invalid_argument(where + ": negative list count " + std::to_string(int64_t(items)));
        declared += size_t(items);
        if (words.size() - w < size_t(items)) return count_mismatch();
        for (size_t k = 0; k < size_t(items); ++k) {
          SOIQ_ASSIGN_OR_RETURN(const double v, ascii_value(words[w++], *p.type, false, where));
          if (p.role == Role::kCorners) sink.corners.push_back(int64_t(v));
        }
      }
      if (w != words.size()) return count_mismatch();
      if (is_vertex) mesh.vertices_mm.push_back(sink.p);
      if (is_face) SOIQ_RETURN_IF_ERROR(sink.add_face([&] { return where; }));
    }
  }
  while (lines.next(line)) {
    words_of(line, words);
    if (!words.empty()) {
      return invalid_argument(line_where("PLY", name, lines.line_number()) + ": data after the last element");
    }
  }
  return ok_status();
}

Status parse_binary_body(const Header& h, std::string_view body, const std::string& name, TriangleMesh& mesh) {
  const bool big = h.format == Format::kBigEndian;
  Sink sink{mesh, h.vertices, {}};
  size_t pos = 0;
  for (const Element& e : h.elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    const auto where = [&](uint64_t item) {
      return "PLY '" + name + "' " + e.name + " " + std::to_string(item + 1) + " (from 1)";
    };
    const auto truncated = [&](uint64_t item) {
      return invalid_argument(where(item) + ": the data ends inside it; is the file truncated?");
    };
    for (uint64_t item = 0; item < e.count; ++item) {
      sink.corners.clear();
      for (const Property& p : e.properties) {
        if (p.count == nullptr) {
          if (body.size() - pos < size_t(p.type->size)) return truncated(item);
          const double v = binary_value(body.data() + pos, p.type->type, big);
          pos += size_t(p.type->size);
          if (p.role == Role::kSkip) continue;
          if (!std::isfinite(v)) return invalid_argument(where(item) + ": coordinate " + p.name + " is not finite");
          sink.coordinate(p.role, v);
          continue;
        }
        if (body.size() - pos < size_t(p.count->size)) return truncated(item);
        const double items = binary_value(body.data() + pos, p.count->type, big);
        pos += size_t(p.count->size);
        if (items < 0) return invalid_argument(where(item) + ": negative list count " + std::to_string(int64_t(items)));
        if ((body.size() - pos) / size_t(p.type->size) < size_t(items)) return truncated(item);
        if (p.role == Role::kCorners) {
          for (size_t k = 0; k < size_t(items); ++k) {
            sink.corners.push_back(
                int64_t(binary_value(body.data() + pos + k * size_t(p.type->size), p.type->type, big)));
          }
        }
        pos += size_t(items) * size_t(p.type->size);
      }
      if (is_vertex) mesh.vertices_mm.push_back(sink.p);
      if (is_face) SOIQ_RETURN_IF_ERROR(sink.add_face([&] { return where(item); }));
    }
  }
  if (pos != body.size()) {
    return invalid_argument("PLY '" + name + "' has " + std::to_string(body.size() - pos) +
                            " bytes after its last element");
  }
  return ok_status();
}
}  // namespace soiq::ply
