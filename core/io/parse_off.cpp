#include "core/io/parse_off.h"

#include <cstdint>
#include <limits>
#include <vector>

#include "core/io/mesh_text.h"

namespace soiq {
namespace {

// The next line with words (comments removed) into `words`; false at the end of the text.
bool next_words(LineReader& lines, std::vector<std::string_view>& words) {
  std::string_view line;
  while (lines.next(line)) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    words_of(line, words);
    if (!words.empty()) return true;
  }
  return false;
}

}  // namespace

Result<TriangleMesh> parse_off(std::string_view bytes, const std::string& name) {
  LineReader lines(bytes);
  std::vector<std::string_view> words;
  if (!next_words(lines, words) || words[0] != "OFF") {
    return invalid_argument("OFF '" + name + "' does not start with the keyword 'OFF'" +
                            (words.empty() ? "" : " (found " + quoted(words[0]) + ")"));
  }
  std::vector<std::string_view> counts(words.begin() + 1, words.end());
  if (counts.empty()) {
    if (!next_words(lines, words)) return invalid_argument("OFF '" + name + "' has no vertex and face counts");
    counts = words;
  }
  std::string where = line_where("OFF", name, lines.line_number());
  if (counts.size() != 3) return invalid_argument(where + ": expected 'vertices faces edges'");
  int64_t n[3];
  for (int k = 0; k < 3; ++k) {
    SOIQ_ASSIGN_OR_RETURN(n[k], whole_integer(counts[k], where));
    if (n[k] < 0) return invalid_argument(where + ": negative count " + std::to_string(n[k]));
  }
  // A vertex line takes at least 6 bytes ("0 0 0\n"), a face line 8 ("3 0 1 2\n"): counts the
  // rest of the file cannot hold are refused before anything is allocated.
  const uint64_t rest = bytes.size() - lines.offset() + 1;
  if (uint64_t(n[0]) > rest / 6 || uint64_t(n[1]) > (rest - uint64_t(n[0]) * 6) / 8) {
    return invalid_argument("OFF '" + name + "' is truncated or corrupt: it announces " + std::to_string(n[0]) +
                            " vertices and " + std::to_string(n[1]) + " faces, but only " +
                            std::to_string(bytes.size() - lines.offset()) + " bytes follow");
  }
  if (n[0] > std::numeric_limits<int32_t>::max()) {
    return resource_exhausted("OFF '" + name + "' has more than 2^31 vertices");
  }
  TriangleMesh mesh;
  mesh.vertices_mm.reserve(size_t(n[0]));
  mesh.triangles.reserve(size_t(n[1]));
  const auto truncated = [&](const char* what, int64_t got, int64_t want) {
    return invalid_argument("OFF '" + name + "' ends after " + std::to_string(got) + " of " + std::to_string(want) +
                            " " + what + "; is it truncated?");
  };
  for (int64_t v = 0; v < n[0]; ++v) {
    if (!next_words(lines, words)) return truncated("vertices", v, n[0]);
    where = line_where("OFF", name, lines.line_number());
    if (words.size() != 3) {
      return invalid_argument(where + ": vertex has " + std::to_string(words.size()) + " values; 3 are needed");
    }
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
      SOIQ_ASSIGN_OR_RETURN(p[a], finite_number(words[a], where));
    }
    mesh.vertices_mm.push_back(p);
  }
  std::vector<int32_t> corners;
  for (int64_t f = 0; f < n[1]; ++f) {
    if (!next_words(lines, words)) return truncated("faces", f, n[1]);
    where = line_where("OFF", name, lines.line_number());
    SOIQ_ASSIGN_OR_RETURN(const int64_t k, whole_integer(words[0], where));
    const int64_t extra = int64_t(words.size()) - 1 - k;  // colour values after the indices
    if (k < 3 || !(extra == 0 || extra == 3 || extra == 4)) {
      return invalid_argument(where + ": face declares " + std::to_string(k) + " corners and has " +
                              std::to_string(words.size() - 1) +
                              " values; a face needs at least 3 corners, optionally followed by a colour");
    }
    corners.clear();
    for (int64_t c = 1; c <= k; ++c) {
      SOIQ_ASSIGN_OR_RETURN(const int64_t index, whole_integer(words[size_t(c)], where));
      if (index < 0 || index >= n[0]) {
        return invalid_argument(where + ": face index " + std::to_string(index) + " is out of range (" +
                                std::to_string(n[0]) + " vertices)");
      }
      corners.push_back(int32_t(index));
    }
    for (size_t c = size_t(k) + 1; c < words.size(); ++c) SOIQ_RETURN_IF_ERROR(finite_number(words[c], where).status());
    for (size_t c = 1; c + 1 < corners.size(); ++c) mesh.triangles.push_back({corners[0], corners[c], corners[c + 1]});
  }
  if (next_words(lines, words)) {
    return invalid_argument(line_where("OFF", name, lines.line_number()) + ": data after the last face");
  }
  return mesh;
}

}  // namespace soiq
