#include "core/geometry/slice_sections.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/geometry/exact_predicates.h"
#include "core/geometry/mesh_defects.h"

namespace soiq {
namespace section_cut {

// An undirected mesh edge, as the two faces sharing it both name it.
uint64_t edge_key(int32_t a, int32_t b) {
  const auto lo = uint64_t(uint32_t(std::min(a, b))), hi = uint64_t(uint32_t(std::max(a, b)));
  return (lo << 32) | hi;
}

// One face's piece of the section on slice k: it enters the face through edge `from` at (x0, y0)
// and leaves it through edge `to` at (x1, y1) (index space).
struct Cut {
  int64_t k;
  uint64_t from, to;
  double x0, y0, x1, y1;
};

struct IndexMesh {
  std::vector<Vec3> v;  // vertices in index space, as the 1D method maps them
};

// Where edge (a, b) meets plane k, given that one end is at or below it and the other above:
// interpolated from the lower end, so both faces sharing the edge get the same point, and a lower
// end lying in the plane is returned exactly.
std::array<double, 2> crossing(const IndexMesh& m, int32_t a, int32_t b, double k) {
  const Vec3& p = m.v[size_t(a)];
  const Vec3& q = m.v[size_t(b)];
  const Vec3& lo = p[2] <= k ? p : q;
  const Vec3& hi = p[2] <= k ? q : p;
  const double t = (k - lo[2]) / (hi[2] - lo[2]);
  return {lo[0] + t * (hi[0] - lo[0]), lo[1] + t * (hi[1] - lo[1])};
}

// Appends the cuts of face (a, b, c) with every plane it spans; plane k lies at z = plane_z[k] in
// the lattice (k itself unless the slices are unevenly spaced).
void cut_face(const IndexMesh& m, const std::array<int32_t, 3>& f, const std::vector<double>& plane_z,
              std::vector<Cut>& out) {
  const double z[3] = {m.v[size_t(f[0])][2], m.v[size_t(f[1])][2], m.v[size_t(f[2])][2]};
  const double zmin = std::min({z[0], z[1], z[2]}), zmax = std::max({z[0], z[1], z[2]});
  // Plane k (perturbed to z_k + d) is cut iff some vertex has z <= z_k and some z > z_k.
  const int64_t k_first = std::lower_bound(plane_z.begin(), plane_z.end(), zmin) - plane_z.begin();
  const int64_t k_last = std::lower_bound(plane_z.begin(), plane_z.end(), zmax) - plane_z.begin() - 1;
  for (int64_t k = k_first; k <= k_last; ++k) {
    const double kd = plane_z[size_t(k)];
    const bool above[3] = {z[0] > kd, z[1] > kd, z[2] > kd};
    // The vertex alone on its side, and the other two in the face's cyclic order.
    int lone = 0;
    if (above[1] != above[0] && above[1] != above[2]) lone = 1;
    if (above[2] != above[0] && above[2] != above[1]) lone = 2;
    const int32_t a = f[size_t(lone)], b = f[size_t((lone + 1) % 3)], c = f[size_t((lone + 2) % 3)];
    // With the lone vertex above, the section runs from edge ab to edge ca: then the outward
    // normal n has z x n along the cut, which puts the inside on its left seen from +k.
    const auto p_ab = crossing(m, a, b, kd), p_ca = crossing(m, c, a, kd);
    if (above[lone])
      out.push_back({k, edge_key(a, b), edge_key(c, a), p_ab[0], p_ab[1], p_ca[0], p_ca[1]});
    else
      out.push_back({k, edge_key(c, a), edge_key(a, b), p_ca[0], p_ca[1], p_ab[0], p_ab[1]});
  }
}

// The points of one loop with repeated consecutive points merged; empty when what is left encloses
// no area (fewer than 3 points, or all on one line, decided exactly).
std::vector<std::array<double, 2>> without_zero_area(std::vector<std::array<double, 2>> loop) {
  std::vector<std::array<double, 2>> out;
  for (const auto& p : loop)
    if (out.empty() || out.back() != p) out.push_back(p);
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  if (out.size() < 3) return {};
  for (size_t i = 2; i < out.size(); ++i)
    if (orient2d_sign(out[0][0], out[0][1], out[1][0], out[1][1], out[i][0], out[i][1]) != 0) return out;
  return {};
}

// Joins the cuts of one slice, [first, last) sorted by `from`, into closed loops: each cut is
// followed by an unused cut entering through the edge it leaves by. On a closed, consistently
// oriented surface every edge is entered as often as it is left on each plane, so the walk can
// only stop where its loop began.
Status join_slice(std::vector<Cut>::const_iterator first, std::vector<Cut>::const_iterator last, const ImageGeometry& g,
                  const std::string& name, std::vector<SliceSection>& out) {
  const size_t n = size_t(last - first);
  std::vector<bool> used(n, false);
  auto next_from = [&](uint64_t edge) -> size_t {
    auto it = std::lower_bound(first, last, edge, [](const Cut& c, uint64_t e) { return c.from < e; });
    for (; it != last && it->from == edge; ++it)
      if (!used[size_t(it - first)]) return size_t(it - first);
    return n;
  };
  const int64_t k = first->k;
  for (size_t start = 0; start < n; ++start) {
    if (used[start]) continue;
    std::vector<std::array<double, 2>> loop;
    size_t at = start;
    while (true) {
      used[at] = true;
      const Cut& c = first[ptrdiff_t(at)];
      loop.push_back({c.x0, c.y0});
      const size_t next = next_from(c.to);
      if (next < n) {
        at = next;
        continue;
      }
      if (c.to != first[ptrdiff_t(start)].from)
        return internal_error("the section of '" + name + "' on slice " + std::to_string(k) +
                              " does not close although the surface is closed; please report this mesh");
      break;
    }
    loop = without_zero_area(std::move(loop));
    if (loop.empty()) continue;
    SliceSection s;
    s.slice = k;
    s.points_mm.reserve(loop.size());
    for (const auto& p : loop) s.points_mm.push_back(g.lattice_to_physical({p[0], p[1], g.lattice_z(double(k))}));
    out.push_back(std::move(s));
  }
  return ok_status();
}

}  // namespace section_cut

Result<std::vector<SliceSection>> slice_sections(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                                 const std::string& name) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  const MeshDefects defects = mesh_defects(mesh);
  SOIQ_RETURN_IF_ERROR(validate_mesh(mesh, defects, name));
  if (!defects.closed())
    return failed_precondition("mesh '" + name + "' is not closed and consistently oriented (" + describe(defects) +
                               "): its sections by the slice planes would not be closed contours; repair it");
  section_cut::IndexMesh m;
  m.v.reserve(mesh.vertices_mm.size());
  for (const Vec3& p : mesh.vertices_mm) m.v.push_back(geometry.physical_to_lattice(p));
  std::vector<double> plane_z(size_t(geometry.dims[2]));
  for (int64_t k = 0; k < geometry.dims[2]; ++k) plane_z[size_t(k)] = geometry.lattice_z(double(k));
  std::vector<section_cut::Cut> cuts;
  for (const auto& f : mesh.triangles) section_cut::cut_face(m, f, plane_z, cuts);
  std::sort(cuts.begin(), cuts.end(), [](const section_cut::Cut& a, const section_cut::Cut& b) {
    return a.k != b.k ? a.k < b.k : a.from < b.from;
  });
  std::vector<SliceSection> out;
  for (auto first = cuts.cbegin(); first != cuts.cend();) {
    auto last = std::find_if(first, cuts.cend(), [&](const section_cut::Cut& c) { return c.k != first->k; });
    SOIQ_RETURN_IF_ERROR(section_cut::join_slice(first, last, geometry, name, out));
    first = last;
  }
  return out;
}

}  // namespace soiq
