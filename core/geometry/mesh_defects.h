#pragma once
// Defects of a surface model that decide whether the 1D method can trust it (docs/DESIGN.md step 6).

#include <cstdint>
#include <string>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

struct MeshDefects {
  int64_t nonfinite_vertices = 0;    // a NaN or infinite coordinate
  int64_t bad_indices = 0;           // triangles with a vertex index outside [0, vertex count)
  int64_t degenerate_triangles = 0;  // repeated vertex index or zero area
  int64_t boundary_edges = 0;        // undirected edges used by exactly one triangle
  int64_t nonmanifold_edges = 0;     // undirected edges used by three or more triangles
  // Edges whose uses do not pair up as a->b with b->a: the surface is not consistently oriented
  // (or not closed), so its winding number is not defined.
  int64_t unbalanced_edges = 0;

  // Watertight and consistently oriented: every directed edge is matched by its reverse.
  bool closed() const { return boundary_edges == 0 && unbalanced_edges == 0; }
  bool operator==(const MeshDefects&) const = default;
};

// Counts the defects. Cost O(T log T) (edges sorted); thread-safe.
MeshDefects mesh_defects(const TriangleMesh& mesh);

// "0 boundary edges, 0 non-manifold edges, 0 degenerate triangles"
std::string describe(const MeshDefects& d);

// INVALID_ARGUMENT when the mesh cannot be processed at all: no triangles, non-finite vertices or
// indices out of range. `name` (a file name or structure name) goes in the message.
Status validate_mesh(const TriangleMesh& mesh, const MeshDefects& d, const std::string& name);

// Signed volume enclosed by the surface, mm³ (sum of signed tetrahedra against the origin): positive
// for outward-oriented closed surfaces. O(T).
double signed_volume_mm3(const TriangleMesh& mesh);

// Flips every triangle when the signed volume is negative, so the surface faces outward.
// Returns true when it flipped.
bool orient_outward(TriangleMesh& mesh);

}  // namespace soiq
