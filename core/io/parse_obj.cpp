#include "core/io/parse_obj.h"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/io/mesh_text.h"

namespace soiq {
namespace {

enum Kind { kVertex = 0, kTexture = 1, kNormal = 2 };
constexpr const char* kKindPlural[3] = {"vertices", "texture coordinates", "normals"};

// The largest positive index of each kind and where it was seen: OBJ files should define a vertex
// before using it, but some writers put faces first, so positive indices are checked at the end
// against the whole file (O(1) memory instead of a list of every index).
struct Forward {
  int64_t index = 0;
  int64_t line = 0;
};

// Resolves one index of a face corner to 0-based; `defined` counts the records of its kind so far.
Result<int64_t> resolve(std::string_view token, std::string_view corner, Kind kind, int64_t defined, Forward& forward,
                        int64_t line, const std::string& where) {
  const Result<int64_t> index = whole_integer(token, where);
  if (!index.ok() || *index == 0) {
    return invalid_argument(where + ": malformed face index " + quoted(corner) +
                            (index.ok() ? " (OBJ indices start at 1)" : ""));
  }
  if (*index < 0 && -*index > defined) {
    return invalid_argument(where + ": face index " + std::to_string(*index) + " is out of range (" +
                            std::to_string(defined) + " " + kKindPlural[kind] + " defined so far)");
  }
  if (*index < 0) return defined + *index;
  if (*index > std::numeric_limits<int32_t>::max()) {
    return invalid_argument(where + ": face index " + std::to_string(*index) + " is out of range");
  }
  if (*index > forward.index) forward = {*index, line};
  return *index - 1;
}

}  // namespace

Result<TriangleMesh> parse_obj(std::string_view bytes, const std::string& name) {
  TriangleMesh mesh;
  int64_t counts[3] = {0, 0, 0};
  Forward forward[3];
  std::vector<int64_t> corners;  // 0-based vertex indices of the face being read
  std::vector<std::string_view> words;
  LineReader lines(bytes);
  std::string_view line;
  while (lines.next(line)) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    words_of(line, words);
    if (words.empty()) continue;
    const std::string_view key = words[0];
    const auto where = [&] { return line_where("OBJ", name, lines.line_number()); };
    if (key == "v") {
      if (words.size() < 4 || words.size() > 8) {
        return invalid_argument(where() + ": vertex has " + std::to_string(words.size() - 1) +
                                " values; 3 are needed (x y z, optionally w or r g b)");
      }
      Vec3 p;
      const std::string w = where();
      for (size_t k = 1; k < words.size(); ++k) {
        SOIQ_ASSIGN_OR_RETURN(const double value, finite_number(words[k], w));
        if (k <= 3) p[k - 1] = value;
      }
      if (counts[kVertex] >= std::numeric_limits<int32_t>::max()) {
        return resource_exhausted("OBJ '" + name + "' has more than 2^31 vertices");
      }
      mesh.vertices_mm.push_back(p);
      ++counts[kVertex];
    } else if (key == "vt" || key == "vn" || key == "vp") {
      const std::string w = where();
      if (words.size() < 2 || words.size() > 5) {
        return invalid_argument(w + ": '" + std::string(key) + "' has " + std::to_string(words.size() - 1) +
                                " values; 1 to 4 are allowed");
      }
      for (size_t k = 1; k < words.size(); ++k) SOIQ_RETURN_IF_ERROR(finite_number(words[k], w).status());
      if (key != "vp") ++counts[key == "vt" ? kTexture : kNormal];
    } else if (key == "f") {
      const std::string w = where();
      if (words.size() < 4) {
        return invalid_argument(w + ": face has " + std::to_string(words.size() - 1) +
                                " corners; a face needs at least 3");
      }
      corners.clear();
      for (size_t k = 1; k < words.size(); ++k) {
        std::string_view rest = words[k];
        for (int kind = kVertex; kind <= kNormal; ++kind) {
          const size_t slash = rest.find('/');
          const std::string_view part = rest.substr(0, slash);
          const bool last = slash == std::string_view::npos;
          if (kind == kVertex || !part.empty()) {
            SOIQ_ASSIGN_OR_RETURN(const int64_t index, resolve(part, words[k], Kind(kind), counts[kind], forward[kind],
                                                               lines.line_number(), w));
            if (kind == kVertex) corners.push_back(index);
          }
          if (last) break;
          if (kind == kNormal) return invalid_argument(w + ": malformed face index " + quoted(words[k]));
          rest = rest.substr(slash + 1);
        }
      }
      for (size_t k = 1; k + 1 < corners.size(); ++k) {
        mesh.triangles.push_back({int32_t(corners[0]), int32_t(corners[k]), int32_t(corners[k + 1])});
      }
    } else if (key == "curv" || key == "curv2" || key == "surf") {
      return invalid_argument(where() + ": free-form geometry ('" + std::string(key) +
                              "') is not supported; export the surface as polygons");
    }
    // Anything else (l, p, g, o, s, usemtl, mtllib, cstype, ...) carries no surface: ignored.
  }
  for (int kind = kVertex; kind <= kNormal; ++kind) {
    if (forward[kind].index > counts[kind]) {
      return invalid_argument(line_where("OBJ", name, forward[kind].line) + ": face index " +
                              std::to_string(forward[kind].index) + " is out of range (the file has " +
                              std::to_string(counts[kind]) + " " + kKindPlural[kind] + ")");
    }
  }
  return mesh;
}

}  // namespace soiq
