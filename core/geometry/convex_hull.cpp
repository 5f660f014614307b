#include "core/geometry/convex_hull.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "core/base/cpu_dispatch.h"
#include "core/geometry/dyadic_lattice.h"
#include "core/geometry/exact_predicates.h"

namespace soiq {
namespace {

// A triangle of the current hull, counter-clockwise seen from outside. adj[e] is the face across
// edge e = (v[e], v[e + 1 mod 3]). Its outside set (points strictly above it, not yet on the hull)
// is a linked list through Quickhull::next_.
struct Face {
  int32_t v[3];
  int32_t adj[3];
  Vec3 origin;   // the position of v0
  Vec3 normal;   // n = u x v with u = v1 - v0, v = v2 - v0 (rounded), unnormalised
  double bound;  // the height filter's error bound for any input point (side())
  int32_t outside = -1, furthest = -1;
  double furthest_distance = 0;
  uint32_t mark = 0;  // visit epoch of the visibility search
  bool visible = false, alive = true;
};

class Quickhull {
 public:
  explicit Quickhull(const std::vector<Vec3>& p)
      : p_(p), next_(p.size(), -1), lattice_(dyadic_lattice_exponent(p).has_value()) {
    Vec3 lo = p[0], hi = p[0];
    for (const Vec3& q : p) {
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
    }
    extent_ = hi - lo;
  }

  Status run() {
    SOIQ_RETURN_IF_ERROR(initial_tetrahedron());
    while (!pending_.empty()) {
      const int32_t f = pending_.back();
      pending_.pop_back();
      if (!faces_[size_t(f)].alive || faces_[size_t(f)].outside < 0) continue;
      add_point(f);
    }
    return ok_status();
  }

  ConvexHull result() const;

 private:
  // The sign of det[b - a; c - a; d - a] (orient3d_sign), exact either way.
  int orient(int32_t a, int32_t b, int32_t c, int32_t d) const {
    const Vec3 &pa = p_[size_t(a)], &pb = p_[size_t(b)], &pc = p_[size_t(c)], &pd = p_[size_t(d)];
    if (!lattice_) return orient3d_sign(pa.data(), pb.data(), pc.data(), pd.data());
    const double det = dot(pb - pa, cross(pc - pa, pd - pa));
    return (det > 0) - (det < 0);
  }
  // The exact sign of q's height over the face's plane, i.e. of orient3d(v0, v1, v2, q), with the
  // unnormalised height h = n . (q - v0) (double) in `height`, which ranks points within a face.
  // On the lattice h is exact: n's components are integers below 2^33 and q - v0's below 2^16
  // (after scaling), so every product and sum is an integer below 2^53. Elsewhere h differs from
  // the exact determinant by at most 16 eps sum_i |w_i| minors_i (w = q - v0): the rounded
  // differences u, v, w perturb each of the determinant's six terms by at most 3 eps relative,
  // n's components carry at most 3 eps of their two products, and the dot product adds 3 eps of
  // sum |n_i w_i|; together under 10 eps of that sum, 16 leaves room for the bound's own
  // rounding. Within the bound the exact predicate decides. |w_i| never exceeds the points'
  // extent along axis i (rounding is monotone), so one bound per face serves every point: the
  // test in the hot loop is a dot product and two compares.
  int side(const Face& f, int32_t q, double& height) const {
    const Vec3 w = p_[size_t(q)] - f.origin;
    height = dot(f.normal, w);
    if (height > f.bound) return 1;
    if (height < -f.bound) return -1;
    if (!lattice_) return orient(f.v[0], f.v[1], f.v[2], q);
    return 0;
  }
  bool above(const Face& f, int32_t q) const {
    double height = 0;
    return side(f, q, height) > 0;
  }

  int32_t new_face(int32_t a, int32_t b, int32_t c) {
    Face f;
    f.v[0] = a, f.v[1] = b, f.v[2] = c;
    f.origin = p_[size_t(a)];
    const Vec3 u = p_[size_t(b)] - f.origin, v = p_[size_t(c)] - f.origin;
    f.normal = cross(u, v);
    if (lattice_) {
      f.bound = 0;  // h is exact
    } else {
      constexpr double kHeightError = 16 * 1.1102230246251565e-16;  // 16 eps, eps = 2^-53
      const Vec3 minors = {std::fabs(u[1] * v[2]) + std::fabs(u[2] * v[1]),
                           std::fabs(u[2] * v[0]) + std::fabs(u[0] * v[2]),
                           std::fabs(u[0] * v[1]) + std::fabs(u[1] * v[0])};
      f.bound = kHeightError * (minors[0] * extent_[0] + minors[1] * extent_[1] + minors[2] * extent_[2]);
    }
    // Dead faces are reused, so memory follows the hull's size, not the number of points added.
    if (!free_faces_.empty()) {
      const int32_t slot = free_faces_.back();
      free_faces_.pop_back();
      faces_[size_t(slot)] = f;
      return slot;
    }
    faces_.push_back(f);
    return int32_t(faces_.size() - 1);
  }

  // Puts q into the outside set of the first face of cone_ it lies strictly above; a point above
  // none is inside or on the hull and is dropped for good. The filter reads the cone's planes
  // from planes_ (set_planes()), packed in cone order, not from the faces scattered in faces_.
  void assign(int32_t q) {
    const Vec3& p = p_[size_t(q)];
    for (size_t c = 0; c < planes_.size(); ++c) {
      const Plane& plane = planes_[c];
      // side()'s height: the same operations in the same order, so the same double.
      double d = plane.normal[0] * (p[0] - plane.origin[0]) + plane.normal[1] * (p[1] - plane.origin[1]) +
                 plane.normal[2] * (p[2] - plane.origin[2]);
      if (!(d > plane.bound)) {
        if (d < -plane.bound || lattice_) continue;
        if (orient(plane.v0, plane.v1, plane.v2, q) <= 0) continue;  // within the bound: exact
      }
      const int32_t f = cone_[c];
      Face& face = faces_[size_t(f)];
      if (face.outside < 0) pending_.push_back(f);
      next_[size_t(q)] = face.outside, face.outside = q;
      if (face.furthest < 0 || d > face.furthest_distance) face.furthest = q, face.furthest_distance = d;
      return;
    }
  }
  void set_planes() {
    planes_.clear();
    for (const int32_t f : cone_) {
      const Face& face = faces_[size_t(f)];
      planes_.push_back({face.normal, face.origin, face.bound, face.v[0], face.v[1], face.v[2]});
    }
  }

  Status initial_tetrahedron();
  void add_point(int32_t start);

  const std::vector<Vec3>& p_;
  std::vector<int32_t> next_;  // outside-set links, by point
  bool lattice_;               // on a small dyadic lattice (dyadic_lattice.h): plain doubles are exact
  Vec3 extent_;                // of the points' bounding box: bounds every |q - origin| component
  std::vector<Face> faces_;
  std::vector<int32_t> pending_;  // faces that got a non-empty outside set; a stack, newest first
                                  // (a reused slot may be listed again: checked when popped)
  std::vector<int32_t> free_faces_, cone_;
  struct Plane {
    Vec3 normal, origin;
    double bound;
    int32_t v0, v1, v2;
  };
  std::vector<Plane> planes_;  // of cone_'s faces, in order
  Vec3 interior_{0, 0, 0};
  uint32_t epoch_ = 0;
  std::vector<int32_t> stack_, visible_;
  struct HorizonEdge {
    int32_t a, b, beyond;  // edge a -> b of a visible face; `beyond` the invisible face across it
  };
  std::vector<HorizonEdge> horizon_;
  std::vector<int32_t> face_from_;  // by point: the new face whose horizon edge starts there
};

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  // Three points are collinear iff all three axis projections are.
  return orient2d_sign(a[0], a[1], b[0], b[1], c[0], c[1]) == 0 &&
         orient2d_sign(a[1], a[2], b[1], b[2], c[1], c[2]) == 0 &&
         orient2d_sign(a[2], a[0], b[2], b[0], c[2], c[0]) == 0;
}

Status Quickhull::initial_tetrahedron() {
  const size_t n = p_.size();
  // The farthest pair among the six axis extremes, then the point farthest from their line, then
  // the one farthest from their plane: a fat start makes most points fall inside at once. The
  // floating-point choices are only heuristics; degeneracy is decided exactly, over all points.
  int32_t ext[6] = {0, 0, 0, 0, 0, 0};
  for (size_t i = 1; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      if (p_[i][a] < p_[size_t(ext[2 * a])][a]) ext[2 * a] = int32_t(i);
      if (p_[i][a] > p_[size_t(ext[2 * a + 1])][a]) ext[2 * a + 1] = int32_t(i);
    }
  }
  int32_t i0 = ext[0], i1 = ext[1];
  double best = -1;
  for (int s = 0; s < 6; ++s) {
    for (int t = s + 1; t < 6; ++t) {
      const Vec3 d = p_[size_t(ext[s])] - p_[size_t(ext[t])];
      if (dot(d, d) > best) best = dot(d, d), i0 = ext[s], i1 = ext[t];
    }
  }
  if (p_[size_t(i0)] == p_[size_t(i1)]) {
    return invalid_argument("convex hull of " + std::to_string(n) + " points is degenerate: they all coincide");
  }
  const Vec3 a = p_[size_t(i0)], axis = p_[size_t(i1)] - a;
  int32_t i2 = -1;
  best = -1;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 c = cross(axis, p_[i] - a);
    if (dot(c, c) > best) best = dot(c, c), i2 = int32_t(i);
  }
  if (collinear(a, p_[size_t(i1)], p_[size_t(i2)])) {
    i2 = -1;
    for (size_t i = 0; i < n && i2 < 0; ++i) {
      if (!collinear(a, p_[size_t(i1)], p_[i])) i2 = int32_t(i);
    }
    if (i2 < 0) {
      return invalid_argument("convex hull of " + std::to_string(n) +
                              " points is degenerate: they are all collinear (no volume)");
    }
  }
  const Vec3 normal = cross(axis, p_[size_t(i2)] - a);
  int32_t i3 = -1;
  best = -1;
  for (size_t i = 0; i < n; ++i) {
    const double d = std::fabs(dot(normal, p_[i] - a));
    if (d > best) best = d, i3 = int32_t(i);
  }
  auto side = [&](int32_t q) { return orient(i0, i1, i2, q); };
  if (side(i3) == 0) {
    i3 = -1;
    for (size_t i = 0; i < n && i3 < 0; ++i) {
      if (side(int32_t(i)) != 0) i3 = int32_t(i);
    }
    if (i3 < 0) {
      return invalid_argument("convex hull of " + std::to_string(n) +
                              " points is degenerate: they are all coplanar (no volume)");
    }
  }
  // Orient so that i3 lies below face (i0, i1, i2); then the other three faces, each an even
  // permutation of the tetrahedron's vertex order, face outward as well.
  if (side(i3) > 0) std::swap(i1, i2);
  const int32_t t[4][3] = {{i0, i1, i2}, {i0, i3, i1}, {i1, i3, i2}, {i2, i3, i0}};
  for (const auto& f : t) cone_.push_back(new_face(f[0], f[1], f[2]));
  // A point strictly inside every later hull, for the volume's tetrahedra.
  interior_ = 0.25 * (p_[size_t(i0)] + p_[size_t(i1)] + p_[size_t(i2)] + p_[size_t(i3)]);
  for (int32_t f = 0; f < 4; ++f) {  // adjacency: the face holding the reversed edge
    for (int e = 0; e < 3; ++e) {
      const int32_t u = faces_[size_t(f)].v[e], w = faces_[size_t(f)].v[(e + 1) % 3];
      for (int32_t g = 0; g < 4; ++g) {
        for (int k = 0; k < 3; ++k) {
          if (faces_[size_t(g)].v[k] == w && faces_[size_t(g)].v[(k + 1) % 3] == u) faces_[size_t(f)].adj[e] = g;
        }
      }
    }
  }
  set_planes();
  for (size_t i = 0; i < n; ++i) {
    const auto q = int32_t(i);
    if (q != i0 && q != i1 && q != i2 && q != i3) assign(q);
  }
  return ok_status();
}

// Adds the furthest point of `start`'s outside set: removes the faces it sees, closes the hole
// with a cone of new faces from the horizon to the point, and hands the removed faces' outside
// points to the cone.
void Quickhull::add_point(int32_t start) {
  const int32_t apex = faces_[size_t(start)].furthest;
  ++epoch_;
  visible_.clear(), horizon_.clear(), stack_.assign(1, start);
  faces_[size_t(start)].mark = epoch_, faces_[size_t(start)].visible = true;
  // The faces the apex lies strictly above form a disc (exact signs: a face the apex is coplanar
  // with stays, and its edge becomes a horizon edge): search it from `start` across edges.
  while (!stack_.empty()) {
    const int32_t f = stack_.back();
    stack_.pop_back();
    visible_.push_back(f);
    for (int e = 0; e < 3; ++e) {
      const int32_t g = faces_[size_t(f)].adj[e];
      Face& other = faces_[size_t(g)];
      if (other.mark != epoch_) {
        other.mark = epoch_;
        other.visible = above(other, apex);
        if (other.visible) stack_.push_back(g);
      }
      if (!other.visible) horizon_.push_back({faces_[size_t(f)].v[e], faces_[size_t(f)].v[(e + 1) % 3], g});
    }
  }
  // The cone: one face (a, b, apex) per horizon edge, linked to the face beyond and, through the
  // horizon's vertices (each starts exactly one horizon edge of the disc's boundary), to its two
  // cone neighbours.
  if (face_from_.size() < p_.size()) face_from_.assign(p_.size(), -1);
  cone_.clear();
  for (const HorizonEdge& h : horizon_) {
    const int32_t f = new_face(h.a, h.b, apex);
    cone_.push_back(f);
    faces_[size_t(f)].adj[0] = h.beyond;
    Face& beyond = faces_[size_t(h.beyond)];
    for (int k = 0; k < 3; ++k) {
      if (beyond.v[k] == h.b && beyond.v[(k + 1) % 3] == h.a) beyond.adj[k] = f;
    }
    face_from_[size_t(h.a)] = f;
  }
  for (const int32_t f : cone_) {
    const int32_t g = face_from_[size_t(faces_[size_t(f)].v[1])];  // the cone face from b: (b, c, apex)
    faces_[size_t(f)].adj[1] = g;
    faces_[size_t(g)].adj[2] = f;
  }
  set_planes();
  for (const int32_t f : visible_) {
    Face& dead = faces_[size_t(f)];
    dead.alive = false;
    for (int32_t q = dead.outside; q >= 0;) {
      const int32_t after = next_[size_t(q)];
      if (q != apex) assign(q);
      q = after;
    }
    dead.outside = -1;
    free_faces_.push_back(f);
  }
}

ConvexHull Quickhull::result() const {
  ConvexHull hull;
  // A hull vertex is a corner iff the faces around it lie in at least three distinct planes, i.e.
  // at least three of its edges are creases (the two faces on an edge are not coplanar): a point
  // inside a facet has none, a point inside a hull edge two.
  std::vector<uint8_t> creases(p_.size(), 0);
  const Vec3& interior = interior_;
  for (size_t f = 0; f < faces_.size(); ++f) {
    const Face& face = faces_[f];
    if (!face.alive) continue;
    hull.triangles.push_back({face.v[0], face.v[1], face.v[2]});
    const Vec3 &a = p_[size_t(face.v[0])], &b = p_[size_t(face.v[1])], &c = p_[size_t(face.v[2])];
    hull.volume_mm3 += dot(a - interior, cross(b - interior, c - interior)) / 6;
    hull.area_mm2 += norm(face.normal) / 2;
    for (int e = 0; e < 3; ++e) {
      const auto g = size_t(face.adj[e]);
      if (g < f) continue;  // each edge once
      const Face& other = faces_[g];
      int32_t opposite = other.v[0];
      for (const int32_t w : other.v) {
        if (w != face.v[e] && w != face.v[(e + 1) % 3]) opposite = w;
      }
      double height = 0;
      if (side(face, opposite, height) != 0) {  // the exact sign, the filter first
        for (const int32_t w : {face.v[e], face.v[(e + 1) % 3]}) {
          if (creases[size_t(w)] < 3) ++creases[size_t(w)];
        }
      }
    }
  }
  for (size_t i = 0; i < p_.size(); ++i) {
    if (creases[i] >= 3) hull.vertex_indices.push_back(int64_t(i));
  }
  return hull;
}

}  // namespace

static Result<ConvexHull> convex_hull_here(const std::vector<Vec3>& points_mm) {
  const size_t n = points_mm.size();
  if (n < 4) return invalid_argument("convex hull needs at least 4 points, got " + std::to_string(n));
  if (n > size_t(INT32_MAX)) {
    return invalid_argument("convex hull of " + std::to_string(n) + " points: more than 2^31-1");
  }
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(points_mm[i][a])) {
        return invalid_argument("convex hull input point " + std::to_string(i) + " has a non-finite coordinate");
      }
    }
  }
  Quickhull quickhull(points_mm);
  SOIQ_RETURN_IF_ERROR(quickhull.run());
  return quickhull.result();
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
Result<ConvexHull> convex_hull(const std::vector<Vec3>& points_mm) {
  return cpu_dispatch([&] { return convex_hull_here(points_mm); });
}

}  // namespace soiq
