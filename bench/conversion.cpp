#include "bench/conversion.h"

#include <memory>

#include "bench/peer_cgal.h"
#include "bench/peer_itk.h"
#include "bench/peer_openvdb.h"
#include "bench/peers_vtk.h"
#include "core/base/run_length_volume.h"
#include "core/reference/voxelize_2d_contours.h"
#include "core/reference/voxelize_3d_raycast.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::bench {

namespace {

// Our methods produce a RunLengthVolume; the timed region includes materialising the dense mask
// so every method delivers the same thing.
Result<Mask> dense(Result<RunLengthVolume> v) {
  if (!v.ok()) return v.status();
  return to_mask(*v);
}

}  // namespace

const char* method_name(Method m) {
  switch (m) {
    case Method::k1d:
      return "1d";
    case Method::k2d:
      return "2d";
    case Method::k3d:
      return "3d";
    case Method::kVtkStencil:
      return "vtk-stencil";
    case Method::kVtkEnclosed:
      return "vtk-enclosed";
    case Method::kItk:
      return "itk";
    case Method::kCgal:
      return "cgal";
    case Method::kOpenVdb:
      return "openvdb";
  }
  return "?";
}

bool method_available(Method m) {
  switch (m) {
    case Method::kItk:
      return itk_available();
    case Method::kCgal:
      return cgal_available();
    case Method::kOpenVdb:
      return openvdb_available();
    default:
      return true;
  }
}

Result<Method> parse_method(const std::string& name) {
  for (Method m : {Method::k1d, Method::k2d, Method::k3d, Method::kVtkStencil, Method::kVtkEnclosed, Method::kItk,
                   Method::kCgal, Method::kOpenVdb}) {
    if (name != method_name(m)) continue;
    if (!method_available(m)) {
      const char* needs = m == Method::kItk    ? "ITK (SOIQ_HAVE_ITK)"
                          : m == Method::kCgal ? "CGAL (SOIQ_HAVE_CGAL)"
                                               : "OpenVDB (SOIQ_HAVE_OPENVDB)";
      return invalid_argument("method '" + name + "' needs a build with " + needs);
    }
    return m;
  }
  return invalid_argument("unknown method '" + name +
                          "'; use 1d, 2d, 3d, vtk-stencil, vtk-enclosed, itk, cgal or openvdb");
}

Result<Conversion> prepare_conversion(Method method, const TriangleMesh& mesh, const ImageGeometry& geometry,
                                      int threads) {
  // The closures share the caller's mesh through a copy held by shared_ptr: preparing is untimed.
  auto m = std::make_shared<const TriangleMesh>(mesh);
  switch (method) {
    case Method::k1d: {
      VoxelizeOptions options;
      options.threads = threads;
      // The mesh's defect check belongs to loading it (the store does it once at upload), as
      // building a vtkPolyData or itk::Mesh belongs to the peers' set-up; `soiq-bench table5`
      // reports its time in a column of its own.
      options.known_defects = mesh_defects(*m);
      return Conversion([m, geometry, options, threads]() -> Result<Mask> {
        auto v = voxelize_1d(*m, geometry, options);
        if (!v.ok()) return v.status();
        return to_mask(v->volume, kDefaultMaxVoxels, threads);
      });
    }
    case Method::k2d:
      return Conversion([m, geometry] { return dense(voxelize_2d_contours(*m, geometry)); });
    case Method::k3d:
      return Conversion([m, geometry] { return dense(voxelize_3d_raycast(*m, geometry)); });
    case Method::kVtkStencil:
      return prepare_vtk_stencil(mesh, geometry);
    case Method::kVtkEnclosed:
      return prepare_vtk_enclosed(mesh, geometry, threads);
    case Method::kItk:
      return prepare_itk(mesh, geometry);
    case Method::kCgal:
      return prepare_cgal(mesh, geometry);
    case Method::kOpenVdb:
      return prepare_openvdb(mesh, geometry, threads);
  }
  return invalid_argument("unknown method");
}

}  // namespace soiq::bench
