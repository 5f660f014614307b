#pragma once
// What parse_mesh (core/io/parse_mesh.h) promises of a mesh it returns: at least one triangle,
// every vertex finite, every index naming a vertex. The mesh harnesses check it on every success.

#include <cmath>

#include "core/base/triangle_mesh.h"
#include "fuzz/require.h"

namespace soiq::fuzz {

inline void check_mesh_contract(const TriangleMesh& mesh) {
  require(!mesh.triangles.empty(), "parse_mesh returned a mesh without triangles");
  for (const auto& v : mesh.vertices_mm)
    require(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]),
            "parse_mesh returned a vertex that is not finite");
  const auto count = int64_t(mesh.vertices_mm.size());
  for (const auto& t : mesh.triangles)
    for (int32_t index : t) require(index >= 0 && index < count, "parse_mesh returned an index out of range");
}

}  // namespace soiq::fuzz
