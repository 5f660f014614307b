#include "bench/peer_openvdb.h"

#ifdef SOIQ_HAVE_OPENVDB
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>
#include <vector>
#endif

// How OpenVDB's result relates to V1 (the voxel-centre test), measured on SM1, SM6 and SM11:
//
// - meshToVolume decides inside and outside by what the exterior reaches: it traces the outside
//   in from the bounding box and fills everything the trace does not reach as interior, whatever
//   the surfaces' orientation. A cavity (the hollow of every simulated model's shell) is
//   therefore filled: on the whole mesh (default flags) 112,931 voxels too many on SM1, 382,997
//   on SM6, 116,475 on SM11. So each connected surface is converted on its own and a voxel is
//   inside when an odd number of them hold it (their masks XORed: the even-odd rule, which for
//   disjoint closed surfaces is the voxel-centre test). Splitting the mesh is set-up; each
//   surface's meshToVolume and its XOR into the mask are timed.
// - DISABLE_RENORMALIZATION: the renormalisation smooths distances where the mesh intersects
//   itself, which these meshes never do, and near the concave crease where a ring's flat face meets
//   the sphere it turns outside voxels inside (1,592 differing voxels on SM6, 3,544 on SM11 with
//   it; 248 and 368 without; no effect on SM1).
// - <= 0 or < 0 makes no difference here: no voxel centre lies on a marching-cubes surface, so no
//   distance is 0.
// What still differs (0 on SM1, 248 on SM6, 368 on SM11) is all voxels OpenVDB has inside and V1
// outside, in that same crease: just outside the sphere (|p| ~ 50 mm) in the voxel layer next to a
// ring's face. OpenVDB gives a voxel within 0.75 voxel of the surface the sign its interior
// neighbours' closest points on the surface point to (ComputeIntersectingVoxelSign), and in a
// crease narrower than a voxel they point the wrong way.

namespace soiq::bench {

#ifdef SOIQ_HAVE_OPENVDB

namespace {

// Double-precision points: libopenvdb ships meshToVolume compiled only for float points (Vec3s).
// Instantiated here for Vec3d it costs this file about a minute of compiling, but the vertices
// reach OpenVDB unrounded and, compiled with soiq-bench's flags, it ran ~13 % faster than the
// library's own copy (best of runs on SM1, SM6 and SM11).
using Adapter = openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3d, openvdb::Vec3I>;

// One connected surface of the mesh: its triangles (indices into the shared point list) and the
// range of voxels whose centres its bounding box holds, clamped to the grid (hi < lo: none).
struct Component {
  std::vector<openvdb::Vec3I> triangles;
  std::array<int32_t, 3> lo{0, 0, 0}, hi{-1, -1, -1};
};

// The mesh as OpenVDB's adapter reads it: index-space points, and the triangles split by connected
// surface.
struct IndexSpaceMesh {
  std::vector<openvdb::Vec3d> points;
  std::vector<Component> components;
};

int32_t find_root(std::vector<int32_t>& parent, int32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// Splits the triangles into surfaces connected through shared vertices, and bounds each one.
std::vector<Component> connected_components(const TriangleMesh& mesh, const std::vector<openvdb::Vec3d>& points,
                                            const ImageGeometry& geometry) {
  std::vector<int32_t> parent(mesh.vertices_mm.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& t : mesh.triangles) {
    for (int c = 1; c < 3; ++c) parent[find_root(parent, t[c])] = find_root(parent, t[0]);
  }
  std::vector<int32_t> component_of(mesh.vertices_mm.size(), -1);
  std::vector<Component> out;
  std::vector<std::array<double, 6>> box;  // min x, y, z, max x, y, z in index space
  for (const auto& t : mesh.triangles) {
    int32_t& c = component_of[find_root(parent, t[0])];
    if (c < 0) {
      c = int32_t(out.size());
      out.emplace_back();
      box.push_back({HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
    }
    out[c].triangles.emplace_back(uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2]));
    for (int v = 0; v < 3; ++v) {
      for (int a = 0; a < 3; ++a) {
        box[c][a] = std::min(box[c][a], points[t[v]][a]);
        box[c][a + 3] = std::max(box[c][a + 3], points[t[v]][a]);
      }
    }
  }
  for (size_t c = 0; c < out.size(); ++c) {
    for (int a = 0; a < 3; ++a) {
      // A voxel centre outside a closed surface's bounding box is outside the surface.
      out[c].lo[a] = int32_t(std::max(0.0, std::ceil(box[c][a])));
      out[c].hi[a] = int32_t(std::min(double(geometry.dims[a] - 1), std::floor(box[c][a + 3])));
    }
  }
  return out;
}

}  // namespace

bool openvdb_available() { return true; }

Result<Conversion> prepare_openvdb(const TriangleMesh& mesh, const ImageGeometry& geometry, int threads) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  // OpenVDB's grid coordinates are int32; a grid beyond that is no benchmark case.
  for (int64_t n : geometry.dims) {
    if (n >= (int64_t(1) << 31)) return invalid_argument("openvdb: grid dimension beyond int32");
  }
  openvdb::initialize();  // registers OpenVDB's types once; idempotent
  auto in = std::make_shared<IndexSpaceMesh>();
  in->points.reserve(mesh.vertices_mm.size());
  for (const Vec3& p : mesh.vertices_mm) {
    const Vec3 q = geometry.physical_to_index(p);
    in->points.emplace_back(q[0], q[1], q[2]);
  }
  in->components = connected_components(mesh, in->points, geometry);

  return Conversion([in, geometry, threads]() -> Result<Mask> {
    Mask m;
    m.geometry = geometry;
    m.voxels.assign(size_t(geometry.voxel_count()), 0);
    const int64_t nx = geometry.dims[0], ny = geometry.dims[1];
    // Voxel size 1 and no offset: OpenVDB's voxel (i,j,k) is the grid's voxel (i,j,k).
    const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    for (const Component& c : in->components) {
      openvdb::FloatGrid::Ptr sdf;
      try {
        // Bands of one voxel each side: only the sign is read, and meshToVolume ends with a
        // signed flood fill that gives every inactive voxel beyond the band its side (-1 inside,
        // +1 outside). The default band of 3 gives the same mask ~25 % slower (measured on SM1,
        // SM6, SM11; 1 and 2 take the same time).
        sdf = openvdb::tools::meshToVolume<openvdb::FloatGrid>(Adapter(in->points, c.triangles), *xform, 1.f, 1.f,
                                                               openvdb::tools::DISABLE_RENORMALIZATION);
      } catch (const openvdb::Exception& e) {
        return internal_error(std::string("openvdb::tools::meshToVolume failed: ") + e.what());
      }
      // One accessor walking i fastest keeps hitting the leaf it cached (8 voxels along i).
      const openvdb::FloatGrid::ConstAccessor acc = sdf->getConstAccessor();
      for (int32_t k = c.lo[2]; k <= c.hi[2]; ++k) {
        for (int32_t j = c.lo[1]; j <= c.hi[1]; ++j) {
          uint8_t* row = m.voxels.data() + nx * (j + ny * int64_t(k));
          for (int32_t i = c.lo[0]; i <= c.hi[0]; ++i) row[i] ^= acc.getValue(openvdb::Coord(i, j, k)) <= 0.f;
        }
      }
    }
    return m;
  });
}

#else

bool openvdb_available() { return false; }

Result<Conversion> prepare_openvdb(const TriangleMesh&, const ImageGeometry&, int) {
  return unimplemented("this soiq-bench was built without OpenVDB; install libopenvdb-dev and rebuild");
}

#endif

}  // namespace soiq::bench
