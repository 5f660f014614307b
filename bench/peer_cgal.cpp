#include "bench/peer_cgal.h"

// CGAL's headers stay in this file, which is compiled on its own (bench/CMakeLists.txt: its own
// object library, with CGAL's -frounding-math, outside the unity batches): they are slow to
// compile and their flags must not reach the rest of soiq-bench.
#ifdef SOIQ_HAVE_CGAL
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <memory>
#include <string>
#include <vector>
#endif

namespace soiq::bench {

#ifdef SOIQ_HAVE_CGAL

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using SideOfMesh = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>;
using Tree = SideOfMesh::AABB_tree;

// The mesh, its AABB tree and the inside test on that tree, kept together at one address: the tree
// refers to the mesh and the test to the tree, so none of them may move once built.
struct Prepared {
  SurfaceMesh mesh;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<SideOfMesh> side;
};

}  // namespace

bool cgal_available() { return true; }

Result<Conversion> prepare_cgal(const TriangleMesh& mesh, const ImageGeometry& geometry) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  auto prepared = std::make_shared<Prepared>();
  SurfaceMesh& sm = prepared->mesh;
  std::vector<SurfaceMesh::Vertex_index> vertex;
  vertex.reserve(mesh.vertices_mm.size());
  for (const Vec3& p : mesh.vertices_mm) vertex.push_back(sm.add_vertex(Point(p[0], p[1], p[2])));
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    // add_face refuses what a halfedge structure cannot hold (an edge with more than two faces,
    // a face against its neighbours' orientation): Side_of_triangle_mesh needs a closed
    // 2-manifold, so such a mesh is this peer's failure, not something to repair here.
    if (sm.add_face(vertex[tri[0]], vertex[tri[1]], vertex[tri[2]]) == SurfaceMesh::null_face()) {
      return failed_precondition("cgal: triangle " + std::to_string(t) +
                                 " does not fit a 2-manifold Surface_mesh (non-manifold edge or flipped face)");
    }
  }
  if (!CGAL::is_closed(sm)) return failed_precondition("cgal: the mesh is not closed");

  // Side_of_triangle_mesh would build its tree lazily on the first query, inside the timed
  // region; built here and handed over, the timed runs only query it.
  prepared->tree = std::make_unique<Tree>(faces(sm).first, faces(sm).second, sm);
  prepared->tree->build();
  prepared->side = std::make_unique<SideOfMesh>(*prepared->tree);

  return Conversion([prepared, geometry]() -> Result<Mask> {
    Mask m;
    m.geometry = geometry;
    m.voxels.assign(size_t(geometry.voxel_count()), 0);
    const auto& d = geometry.dims;
    size_t n = 0;
    for (int64_t k = 0; k < d[2]; ++k) {
      for (int64_t j = 0; j < d[1]; ++j) {
        for (int64_t i = 0; i < d[0]; ++i, ++n) {
          const Vec3 c = geometry.index_to_physical({double(i), double(j), double(k)});
          // A centre on the surface counts as inside (the closed set), as the voxel-centre rule of
          // V1 would; none of the simulated models' centres is on their marching-cubes surface.
          m.voxels[n] = (*prepared->side)(Point(c[0], c[1], c[2])) != CGAL::ON_UNBOUNDED_SIDE;
        }
      }
    }
    return m;
  });
}

#else

bool cgal_available() { return false; }

Result<Conversion> prepare_cgal(const TriangleMesh&, const ImageGeometry&) {
  return unimplemented("this soiq-bench was built without CGAL; install libcgal-dev and rebuild");
}

#endif

}  // namespace soiq::bench
