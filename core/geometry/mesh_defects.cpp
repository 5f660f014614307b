#include "core/geometry/mesh_defects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/base/cpu_dispatch.h"

namespace soiq {

namespace {

// Every undirected edge {a, b} (a < b), stored once per use at its smaller end a as
// 2*b + (1 if the use runs a->b else 0), grouped by a with a counting sort and sorted within each
// group. Uses of one edge are then adjacent, and nothing is looked up at the other end, which
// keeps the pass close to memory speed: it guards every conversion, so it must cost less than the
// conversion itself. Sorting the groups also keeps a hostile vertex of huge degree from going
// quadratic.
struct EdgeUses {
  std::vector<int64_t> start;  // per vertex
  std::vector<int64_t> uses;
};

EdgeUses edge_uses(const TriangleMesh& mesh, const std::vector<uint8_t>& usable) {
  const size_t nv = mesh.vertices_mm.size();
  EdgeUses g;
  g.start.assign(nv + 1, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!usable[t]) continue;
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) ++g.start[size_t(std::min(tri[c], tri[(c + 1) % 3])) + 1];
  }
  for (size_t v = 0; v < nv; ++v) g.start[v + 1] += g.start[v];
  g.uses.resize(size_t(g.start[nv]));
  std::vector<int64_t> fill(g.start.begin(), g.start.end() - 1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!usable[t]) continue;
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) {
      const int32_t a = tri[c], b = tri[(c + 1) % 3];
      const int32_t lo = std::min(a, b), hi = std::max(a, b);
      g.uses[size_t(fill[size_t(lo)]++)] = 2 * int64_t(hi) + (a < b ? 1 : 0);
    }
  }
  for (size_t v = 0; v < nv; ++v) {
    int64_t* first = g.uses.data() + g.start[v];
    int64_t* last = g.uses.data() + g.start[v + 1];
    if (last - first > 16) {
      std::sort(first, last);
      continue;
    }
    // Most vertices have a handful of edges: an insertion sort without std::sort's set-up.
    for (int64_t* i = first + 1; i < last; ++i) {
      const int64_t key = *i;
      int64_t* j = i;
      for (; j > first && *(j - 1) > key; --j) *j = *(j - 1);
      *j = key;
    }
  }
  return g;
}

}  // namespace

static MeshDefects mesh_defects_here(const TriangleMesh& mesh) {
  MeshDefects d;
  const int64_t nv = int64_t(mesh.vertices_mm.size());
  for (const Vec3& p : mesh.vertices_mm) {
    d.nonfinite_vertices += !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  }
  // Triangles that reference missing vertices cannot take part in the edge analysis.
  std::vector<uint8_t> usable(mesh.triangles.size(), 1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    bool in_range = true;
    for (int c = 0; c < 3; ++c) in_range = in_range && tri[c] >= 0 && tri[c] < nv;
    if (!in_range) {
      ++d.bad_indices;
      usable[t] = 0;
      continue;
    }
    const Vec3& a = mesh.vertices_mm[size_t(tri[0])];
    const Vec3& b = mesh.vertices_mm[size_t(tri[1])];
    const Vec3& c = mesh.vertices_mm[size_t(tri[2])];
    const Vec3 n = cross(b - a, c - a);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || (n[0] == 0 && n[1] == 0 && n[2] == 0)) {
      ++d.degenerate_triangles;
    }
  }

  const EdgeUses g = edge_uses(mesh, usable);
  for (size_t v = 0; v + 1 < g.start.size(); ++v) {
    for (int64_t e = g.start[v]; e < g.start[v + 1];) {
      const int64_t edge = g.uses[size_t(e)] >> 1;
      int64_t forward = 0, backward = 0;
      for (; e < g.start[v + 1] && (g.uses[size_t(e)] >> 1) == edge; ++e) {
        (g.uses[size_t(e)] & 1 ? forward : backward) += 1;
      }
      const int64_t uses = forward + backward;
      d.boundary_edges += uses == 1;
      d.nonmanifold_edges += uses >= 3;
      d.unbalanced_edges += forward != backward;
    }
  }
  return d;
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
MeshDefects mesh_defects(const TriangleMesh& mesh) {
  return cpu_dispatch([&] { return mesh_defects_here(mesh); });
}

std::string describe(const MeshDefects& d) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%lld boundary edges, %lld non-manifold edges, %lld degenerate triangles",
                (long long)d.boundary_edges, (long long)d.nonmanifold_edges, (long long)d.degenerate_triangles);
  std::string s = buf;
  if (d.unbalanced_edges > d.boundary_edges) {
    s += ", " + std::to_string(d.unbalanced_edges - d.boundary_edges) + " inconsistently oriented edges";
  }
  return s;
}

Status validate_mesh(const TriangleMesh& mesh, const MeshDefects& d, const std::string& name) {
  if (mesh.triangles.empty()) return invalid_argument("mesh '" + name + "' has no triangles");
  if (d.nonfinite_vertices > 0) {
    return invalid_argument("mesh '" + name + "' has " + std::to_string(d.nonfinite_vertices) +
                            " vertices with NaN or infinite coordinates");
  }
  if (d.bad_indices > 0) {
    return invalid_argument("mesh '" + name + "' has " + std::to_string(d.bad_indices) +
                            " triangles with vertex indices out of range (it has " +
                            std::to_string(mesh.vertices_mm.size()) + " vertices)");
  }
  return ok_status();
}

double signed_volume_mm3(const TriangleMesh& mesh) {
  // Tetrahedra against the first vertex rather than the origin: the same sum for a closed
  // surface, with less cancellation for meshes far from the origin (scanner coordinates).
  if (mesh.vertices_mm.empty()) return 0;
  const Vec3 o = mesh.vertices_mm[0];
  double six_v = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices_mm[size_t(t[0])] - o;
    const Vec3 b = mesh.vertices_mm[size_t(t[1])] - o;
    const Vec3 c = mesh.vertices_mm[size_t(t[2])] - o;
    six_v += dot(a, cross(b, c));
  }
  return six_v / 6.0;
}

bool orient_outward(TriangleMesh& mesh) {
  if (signed_volume_mm3(mesh) >= 0) return false;
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return true;
}

}  // namespace soiq
