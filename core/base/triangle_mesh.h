#pragma once
// A surface model: vertices in LPS millimetres and triangles as vertex-index triples. Closed
// surfaces are oriented with outward normals (counter-clockwise seen from outside).

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/vec3.h"

namespace soiq {

struct TriangleMesh {
  std::vector<Vec3> vertices_mm;
  std::vector<std::array<int32_t, 3>> triangles;
};

}  // namespace soiq
