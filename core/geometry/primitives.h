#pragma once
// Closed, outward-oriented triangle meshes of simple shapes, in LPS mm: test fixtures, benchmark
// inputs and the synthetic cohort. Each is watertight (every edge shared by exactly two triangles).

#include <cstdint>

#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"

namespace soiq {

// A UV sphere: `rings` >= 2 latitude bands and `segments` >= 3 longitudes; 2*segments*(rings-1)
// triangles. Vertices lie on the sphere, so the mesh is inscribed (slightly smaller).
TriangleMesh uv_sphere(const Vec3& centre_mm, double radius_mm, int rings, int segments);

// A UV sphere with about `triangles` triangles (rings ~ segments / 2).
TriangleMesh uv_sphere_with_triangles(const Vec3& centre_mm, double radius_mm, int64_t triangles);

// A torus around the z axis: ring radius R, tube radius r < R; 2*n_major*n_minor triangles.
TriangleMesh torus(const Vec3& centre_mm, double major_radius_mm, double minor_radius_mm, int n_major, int n_minor);

// An axis-aligned box [lo, hi]; 12 triangles.
TriangleMesh box(const Vec3& lo_mm, const Vec3& hi_mm);

// Appends b's triangles to a (a union of closed components, possibly overlapping).
TriangleMesh merge(const TriangleMesh& a, const TriangleMesh& b);

// Reverses every triangle (inward normals); used to build hollow shells and to test orientation.
TriangleMesh flipped(const TriangleMesh& m);

// The rotation by `angle` radians about `axis` (any non-zero length; Rodrigues' formula).
Mat3 rotation_about(const Vec3& axis, double angle);

// Every vertex v -> centre + r (scale * v), scale per axis: ellipsoids from spheres, oblique shapes.
// A rotation and a positive scale keep the mesh closed and outward.
TriangleMesh transformed(TriangleMesh m, const Vec3& scale, const Mat3& r, const Vec3& centre);

}  // namespace soiq
