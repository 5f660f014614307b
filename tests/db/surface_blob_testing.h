#pragma once
// Test support for the surface blob's tests (surface_blob_test.cpp, surface_blob_checksum_test.cpp):
// meshes (random, with the values a lossy encoding would get wrong; a smooth sphere), bitwise
// comparison, and blobs of every version built by hand: version 1 from canonical bytes, version 2
// from a version 3 blob.

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "core/base/triangle_mesh.h"
#include "db/deflate.h"

namespace soiq::db::testing {

// Bitwise equality: == on doubles would accept -0.0 for +0.0.
inline bool same_bits(const TriangleMesh& a, const TriangleMesh& b) {
  return a.vertices_mm.size() == b.vertices_mm.size() && a.triangles == b.triangles &&
         (a.vertices_mm.empty() ||
          std::memcmp(a.vertices_mm.data(), b.vertices_mm.data(), a.vertices_mm.size() * sizeof(Vec3)) == 0);
}

inline TriangleMesh random_mesh(std::mt19937_64& rng, size_t nv, size_t nt) {
  // Ordinary values mixed with the ones a lossy encoding would get wrong.
  const double specials[] = {0.0,
                             -0.0,
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min() / 3,
                             std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(),
                             1e300,
                             0.1,
                             1.0 / 3.0};
  std::uniform_real_distribution<double> coord(-500, 500);
  std::uniform_int_distribution<int> pick(0, 19);
  TriangleMesh m;
  for (size_t i = 0; i < nv; ++i) {
    Vec3 v;
    for (double& x : v) {
      const int k = pick(rng);
      x = k < 10 ? specials[k] : coord(rng);
    }
    m.vertices_mm.push_back(v);
  }
  std::uniform_int_distribution<int32_t> index(0, int32_t(nv) - 1);
  for (size_t t = 0; t < nt; ++t) m.triangles.push_back({index(rng), index(rng), index(rng)});
  return m;
}

// Builds a blob from canonical bytes written by hand, to reach the checks behind zlib.
inline std::string blob_of(const std::string& canonical) { return *deflate_bytes(canonical.data(), canonical.size()); }

inline std::string header(uint32_t version, uint64_t nv, uint64_t nt) {
  std::string h("SOIQSURF", 8);
  h.append(reinterpret_cast<const char*>(&version), 4);
  h.append(4, '\0');
  h.append(reinterpret_cast<const char*>(&nv), 8);
  h.append(reinterpret_cast<const char*>(&nt), 8);
  return h;
}

// Version 1's canonical bytes of `m`: what the sha256 is taken over, and deflated, a version 1 blob.
inline std::string canonical_bytes(const TriangleMesh& m) {
  std::string c = header(1, m.vertices_mm.size(), m.triangles.size());
  c.append(reinterpret_cast<const char*>(m.vertices_mm.data()), m.vertices_mm.size() * sizeof(Vec3));
  c.append(reinterpret_cast<const char*>(m.triangles.data()), m.triangles.size() * 12);
  return c;
}

// The version 2 blob of the same mesh: version 3 without its checksum, under version 2's magic
// (db/surface_blob.cpp: magic, CRC-32, then what version 2 holds after its magic).
inline std::string version2_of(const std::string& v3) { return std::string("SOIQSRF2", 8) + v3.substr(12); }

// A smooth sphere of `rings` x 240 vertices: its planes compress, so its blocks are LZ4's.
inline TriangleMesh smooth_sphere(int rings) {
  const int segments = 240;
  TriangleMesh m;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double th = 3.14159265358979 * r / rings, ph = 2 * 3.14159265358979 * s / segments;
      m.vertices_mm.push_back({20 * std::sin(th) * std::cos(ph), 20 * std::sin(th) * std::sin(ph), 20 * std::cos(th)});
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      m.triangles.push_back({a, b, a + segments});
      m.triangles.push_back({b, b + segments, a + segments});
    }
  }
  return m;
}

}  // namespace soiq::db::testing
