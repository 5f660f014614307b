#include "core/mesh_defects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace soiq {

namespace {

// Directed edges a->b grouped by source vertex a (a counting sort, O(T + V)) and sorted within
// each group: out-neighbours of a are targets[start[a] .. start[a+1]). Near-linear time keeps the
// closedness check well below the cost of the voxelization it guards, and sorting the groups
// keeps a hostile vertex of huge degree (a fan of a million triangles) from going quadratic.
struct OutEdges {
  std::vector<int64_t> start;
  std::vector<int32_t> targets;

  int64_t count(int32_t from, int32_t to) const {
    const auto first = targets.begin() + start[size_t(from)];
    const auto last = targets.begin() + start[size_t(from) + 1];
    const auto range = std::equal_range(first, last, to);
    return range.second - range.first;
  }
  // True when position e holds the first copy of its target (so each edge is visited once).
  bool first_at(int32_t from, int64_t e) const {
    return e == start[size_t(from)] || targets[size_t(e) - 1] != targets[size_t(e)];
  }
};

OutEdges out_edges(const TriangleMesh& mesh, const std::vector<bool>& usable) {
  const size_t nv = mesh.vertices_mm.size();
  OutEdges g;
  g.start.assign(nv + 1, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!usable[t]) continue;
    for (int c = 0; c < 3; ++c) ++g.start[size_t(mesh.triangles[t][c]) + 1];
  }
  for (size_t v = 0; v < nv; ++v) g.start[v + 1] += g.start[v];
  g.targets.resize(size_t(g.start[nv]));
  std::vector<int64_t> fill(g.start.begin(), g.start.end() - 1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!usable[t]) continue;
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) g.targets[size_t(fill[size_t(tri[c])]++)] = tri[(c + 1) % 3];
  }
  for (size_t v = 0; v < nv; ++v) std::sort(g.targets.begin() + g.start[v], g.targets.begin() + g.start[v + 1]);
  return g;
}

}  // namespace

MeshDefects mesh_defects(const TriangleMesh& mesh) {
  MeshDefects d;
  const int64_t nv = int64_t(mesh.vertices_mm.size());
  for (const Vec3& p : mesh.vertices_mm) {
    d.nonfinite_vertices += !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  }
  // Triangles that reference missing vertices cannot take part in the edge analysis.
  std::vector<bool> usable(mesh.triangles.size(), true);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    bool in_range = true;
    for (int c = 0; c < 3; ++c) in_range = in_range && tri[c] >= 0 && tri[c] < nv;
    if (!in_range) {
      ++d.bad_indices;
      usable[t] = false;
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

  const OutEdges g = out_edges(mesh, usable);
  for (int32_t a = 0; a < int32_t(nv); ++a) {
    for (int64_t e = g.start[a]; e < g.start[a + 1]; ++e) {
      const int32_t b = g.targets[size_t(e)];
      if (!g.first_at(a, e)) continue;
      const int64_t forward = g.count(a, b);
      const int64_t backward = g.count(b, a);
      // Visit each undirected edge once: from its smaller end, or from its only end.
      if (a > b && backward > 0) continue;
      const int64_t uses = forward + backward;
      d.boundary_edges += uses == 1;
      d.nonmanifold_edges += uses >= 3;
      d.unbalanced_edges += forward != backward;
    }
  }
  return d;
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
