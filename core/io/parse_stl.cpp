#include "core/io/parse_stl.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

#include "core/io/byte_order.h"
#include "core/io/mesh_text.h"

namespace soiq {
namespace {

constexpr size_t kBinaryHeaderBytes = 84;  // 80 bytes of text, then the uint32 facet count
constexpr size_t kBinaryFacetBytes = 50;   // normal, three corners (12 float32), 2 attribute bytes

// Gives each distinct corner one vertex index, in first-seen order (vtkMergePoints' order).
class CornerMerger {
 public:
  explicit CornerMerger(TriangleMesh& mesh, size_t expected_corners) : mesh_(mesh) {
    index_.reserve(expected_corners / 2);
  }

  int32_t index_of(Vec3 p) {
    // -0.0 == +0.0, as vtkMergePoints compares them: one key for both.
    for (double& c : p) c += 0.0;
    const auto [it, inserted] = index_.try_emplace(p, int32_t(mesh_.vertices_mm.size()));
    if (inserted) mesh_.vertices_mm.push_back(p);
    return it->second;
  }

  // Appends the facet unless two corners merged into one vertex.
  void add_facet(const std::array<Vec3, 3>& corners) {
    const std::array<int32_t, 3> t = {index_of(corners[0]), index_of(corners[1]), index_of(corners[2])};
    if (t[0] != t[1] && t[0] != t[2] && t[1] != t[2]) mesh_.triangles.push_back(t);
  }

 private:
  struct Hash {
    size_t operator()(const Vec3& p) const {
      uint64_t h = 0x9e3779b97f4a7c15ull;
      for (const double c : p) {
        uint64_t bits;
        std::memcpy(&bits, &c, sizeof bits);
        h = (h ^ bits) * 0x100000001b3ull;
        h ^= h >> 29;
      }
      return size_t(h);
    }
  };
  TriangleMesh& mesh_;
  std::unordered_map<Vec3, int32_t, Hash> index_;
};

bool equals_lower(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (size_t i = 0; i < word.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(word[i])) != keyword[i]) return false;
  }
  return true;
}

// ASCII when the text starts with "solid" and the first 84 bytes hold no NUL: binary headers that
// also start with "solid" are caught by their exact size first, and a truncated one usually has
// zero bytes in its facet count.
bool looks_ascii(std::string_view bytes) {
  size_t i = 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  if (bytes.size() - i < 5 || !equals_lower(bytes.substr(i, 5), "solid")) return false;
  return bytes.substr(0, kBinaryHeaderBytes).find('\0') == std::string_view::npos;
}

Result<TriangleMesh> parse_binary(std::string_view bytes, uint32_t facets, const std::string& name) {
  TriangleMesh mesh;
  mesh.triangles.reserve(facets);
  mesh.vertices_mm.reserve(facets / 2 + 3);  // a closed surface has about half as many vertices as facets
  CornerMerger merger(mesh, 3 * size_t(facets));
  const char* p = bytes.data() + kBinaryHeaderBytes;
  for (uint32_t f = 0; f < facets; ++f, p += kBinaryFacetBytes) {
    std::array<Vec3, 3> corners;
    for (int c = 0; c < 3; ++c) {
      for (int a = 0; a < 3; ++a) {
        const float v = load_scalar<float>(p + 12 * (c + 1) + 4 * a, /*big_endian=*/false);
        if (!std::isfinite(v)) {
          return invalid_argument("binary STL '" + name + "' facet " + std::to_string(f + 1) + " corner " +
                                  std::to_string(c + 1) + " has a non-finite coordinate");
        }
        corners[c][a] = double(v);
      }
    }
    merger.add_facet(corners);
  }
  return mesh;
}

Result<TriangleMesh> parse_ascii(std::string_view bytes, const std::string& name) {
  enum class Expect { kSolid, kFacet, kOuterLoop, kVertex, kEndLoop, kEndFacet };
  static constexpr const char* kExpected[] = {
      "solid", "facet normal' or 'endsolid", "outer loop", "vertex", "endloop", "endfacet"};
  TriangleMesh mesh;
  // The smallest facet ("facet normal 0 0 0 outer loop vertex 0 0 0 ..." one per line) has more
  // than 80 bytes: a bound on the facets without trusting anything in the file.
  CornerMerger merger(mesh, 3 * (bytes.size() / 80));
  Expect expect = Expect::kSolid;
  std::array<Vec3, 3> corners;
  int corner = 0;
  bool any_solid = false;
  LineReader lines(bytes);
  std::vector<std::string_view> words;
  std::string_view line;
  while (lines.next(line)) {
    words_of(line, words);
    if (words.empty()) continue;
    const std::string where = line_where("STL", name, lines.line_number());
    const std::string_view key = words[0];
    auto expect_words = [&](size_t n, std::string_view what) -> Status {
      if (words.size() == n) return ok_status();
      return invalid_argument(where + ": '" + std::string(what) + "' takes " + std::to_string(n - 1) +
                              " values, found " + std::to_string(words.size() - 1));
    };
    switch (expect) {
      case Expect::kSolid:
        if (!equals_lower(key, "solid")) break;
        any_solid = true;
        expect = Expect::kFacet;
        continue;
      case Expect::kFacet:
        if (equals_lower(key, "endsolid")) {
          expect = Expect::kSolid;
          continue;
        }
        if (!equals_lower(key, "facet") || words.size() < 2 || !equals_lower(words[1], "normal")) break;
        if (words.size() != 5) {
          return invalid_argument(where + ": 'facet normal' takes 3 values, found " + std::to_string(words.size() - 2));
        }
        for (size_t w = 2; w < 5; ++w) SOIQ_RETURN_IF_ERROR(any_number(words[w], where).status());
        expect = Expect::kOuterLoop;
        continue;
      case Expect::kOuterLoop:
        if (!equals_lower(key, "outer") || words.size() != 2 || !equals_lower(words[1], "loop")) break;
        expect = Expect::kVertex;
        continue;
      case Expect::kVertex:
        if (!equals_lower(key, "vertex")) break;
        SOIQ_RETURN_IF_ERROR(expect_words(4, "vertex"));
        for (int a = 0; a < 3; ++a) {
          SOIQ_ASSIGN_OR_RETURN(corners[corner][a], finite_number(words[1 + a], where));
        }
        if (++corner == 3) {
          corner = 0;
          merger.add_facet(corners);
          expect = Expect::kEndLoop;
        }
        continue;
      case Expect::kEndLoop:
        if (!equals_lower(key, "endloop")) break;
        SOIQ_RETURN_IF_ERROR(expect_words(1, "endloop"));
        expect = Expect::kEndFacet;
        continue;
      case Expect::kEndFacet:
        if (!equals_lower(key, "endfacet")) break;
        SOIQ_RETURN_IF_ERROR(expect_words(1, "endfacet"));
        expect = Expect::kFacet;
        continue;
    }
    return invalid_argument(where + ": expected '" + kExpected[int(expect)] + "', found " + quoted(key));
  }
  if (!any_solid) return invalid_argument("STL '" + name + "' has no 'solid' line");
  if (expect != Expect::kSolid) {
    return invalid_argument("STL '" + name + "' ends (line " + std::to_string(lines.line_number()) + ") where '" +
                            kExpected[int(expect)] + "' was expected; is it truncated?");
  }
  return mesh;
}

}  // namespace

Result<TriangleMesh> parse_stl(std::string_view bytes, const std::string& name) {
  uint32_t facets = 0;
  if (bytes.size() >= kBinaryHeaderBytes) facets = load_scalar<uint32_t>(bytes.data() + 80, /*big_endian=*/false);
  const uint64_t expected = kBinaryHeaderBytes + kBinaryFacetBytes * uint64_t(facets);
  if (bytes.size() >= kBinaryHeaderBytes && expected == bytes.size()) return parse_binary(bytes, facets, name);
  if (looks_ascii(bytes)) return parse_ascii(bytes, name);
  if (bytes.size() < kBinaryHeaderBytes) {
    return invalid_argument("binary STL '" + name + "' is truncated: " + std::to_string(bytes.size()) +
                            " bytes, less than the 84-byte header");
  }
  return invalid_argument("binary STL '" + name + "' is truncated or corrupt: its header announces " +
                          std::to_string(facets) + " triangles (" + std::to_string(expected) +
                          " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
}

}  // namespace soiq
