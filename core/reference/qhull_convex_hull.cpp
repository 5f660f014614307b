#include "core/reference/qhull_convex_hull.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace soiq {
namespace {

// A FILE* that collects everything Qhull writes, so it never reaches stderr and its error text can
// go into a Status. POSIX open_memstream; the buffer is valid after fclose.
class MessageStream {
 public:
  MessageStream() { file_ = open_memstream(&buffer_, &size_); }
  ~MessageStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  MessageStream(const MessageStream&) = delete;
  MessageStream& operator=(const MessageStream&) = delete;
  FILE* file() const { return file_; }
  // The first line that names an error ("QH6154 qhull input error: ..."), else the first line.
  std::string first_error_line() {
    if (file_ != nullptr) std::fclose(file_), file_ = nullptr;
    const std::string text = buffer_ != nullptr ? std::string(buffer_, size_) : std::string();
    size_t start = text.find("QH");
    if (start == std::string::npos) start = 0;
    const size_t end = text.find('\n', start);
    return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
  }

 private:
  FILE* file_ = nullptr;
  char* buffer_ = nullptr;
  size_t size_ = 0;
};

// Owns one reentrant Qhull context and frees all of its memory, whatever happened.
class QhullContext {
 public:
  explicit QhullContext(FILE* err) : qh_(std::make_unique<qhT>()) { qh_zero(qh_.get(), err); }
  ~QhullContext() {
    int curlong = 0, totlong = 0;
    qh_freeqhull(qh_.get(), !qh_ALL);
    qh_memfreeshort(qh_.get(), &curlong, &totlong);
  }
  QhullContext(const QhullContext&) = delete;
  QhullContext& operator=(const QhullContext&) = delete;
  qhT* get() const { return qh_.get(); }

 private:
  std::unique_ptr<qhT> qh_;
};

}  // namespace

Result<ConvexHull> qhull_convex_hull(const std::vector<Vec3>& points_mm) {
  const size_t n = points_mm.size();
  if (n < 4) return invalid_argument("convex hull needs at least 4 points, got " + std::to_string(n));
  if (n > size_t(INT_MAX))
    return invalid_argument("convex hull of " + std::to_string(n) + " points: too many for Qhull");
  std::vector<coordT> coords(3 * n);
  for (size_t p = 0; p < n; ++p) {
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(points_mm[p][a])) {
        return invalid_argument("convex hull input point " + std::to_string(p) + " has a non-finite coordinate");
      }
      coords[3 * p + a] = points_mm[p][a];
    }
  }

  MessageStream messages;
  if (messages.file() == nullptr) return internal_error("convex hull: cannot open a memory stream for Qhull");
  QhullContext context(messages.file());
  qhT* qh = context.get();
  char command[] = "qhull Qt";  // Qhull wants a mutable string
  const int exitcode = qh_new_qhull(qh, 3, int(n), coords.data(), False, command, nullptr, messages.file());
  if (exitcode != 0) {
    const std::string why = messages.first_error_line();
    if (exitcode == qh_ERRsingular || exitcode == qh_ERRinput) {
      return invalid_argument("convex hull of " + std::to_string(n) +
                              " points is degenerate (coplanar or collinear points?): " + why);
    }
    return internal_error("Qhull failed with exit code " + std::to_string(exitcode) + ": " + why);
  }

  ConvexHull hull;
  vertexT* vertex = nullptr;
  FORALLvertices { hull.vertex_indices.push_back(qh_pointid(qh, vertex->point)); }
  std::sort(hull.vertex_indices.begin(), hull.vertex_indices.end());
  // An interior reference point: the mean of the hull vertices (strictly inside a 3D hull). Every
  // tetrahedron (interior, triangle) then has positive volume, which also tells the outward order.
  Vec3 interior{0, 0, 0};
  for (const int64_t v : hull.vertex_indices) interior = interior + points_mm[size_t(v)];
  interior = (1.0 / double(hull.vertex_indices.size())) * interior;

  facetT* facet = nullptr;
  FORALLfacets {
    std::array<int64_t, 3> t{};
    int count = 0;
    vertexT** vertexp = nullptr;
    FOREACHvertex_(facet->vertices) {
      if (count < 3) t[count] = qh_pointid(qh, vertex->point);
      ++count;
    }
    // 'Qt' makes every facet a triangle; anything else would be a Qhull contract violation.
    if (count != 3) return internal_error("Qhull returned a facet with " + std::to_string(count) + " vertices");
    const Vec3& a = points_mm[size_t(t[0])];
    const Vec3 normal = cross(points_mm[size_t(t[1])] - a, points_mm[size_t(t[2])] - a);
    const double six_volume = dot(normal, a - interior);
    if (six_volume < 0) std::swap(t[1], t[2]);
    hull.volume_mm3 += std::fabs(six_volume) / 6;
    hull.area_mm2 += norm(normal) / 2;
    hull.triangles.push_back(t);
  }
  return hull;
}

}  // namespace soiq
