#include "bench/table7.h"

#include <cstdio>

#include "bench/method_run.h"
#include "core/base/run_length_volume.h"
#include "core/geometry/primitives.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::bench {

int run_table7(const CliArgs& args) {
  const Result<int> runs = args.get_int("--runs", 3);
  const Result<int> pin = args.get_int("--pin", 0);
  if (!runs.ok() || !pin.ok()) {
    std::fprintf(stderr, "usage: soiq-bench table7 [--runs N] [--pin CPU]\n");
    return 2;
  }
  std::printf(
      "UV spheres, radius 20 mm, 0.5 mm grid with a 2-voxel margin; best ms, 1 thread pinned; "
      "1d up to %d runs, 3d and vtk-enclosed 1 run\n\n",
      *runs);
  std::printf(
      "| triangles | vertices | grid voxels | inside | 1d ms | 3d ms | vtk-enclosed ms | 3d differing | "
      "vtk-enclosed differing |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int64_t triangles : {500, 2000, 8000, 32000, 128000}) {
    const TriangleMesh mesh = uv_sphere_with_triangles({0.3, -0.2, 0.1}, 20, triangles);
    const Result<ImageGeometry> grid = grid_around(mesh, {0.5, 0.5, 0.5}, 2);
    if (!grid.ok()) {
      std::fprintf(stderr, "table7: %s\n", grid.status().to_string().c_str());
      return 1;
    }
    const auto ours = voxelize_1d(mesh, *grid);
    if (!ours.ok()) {
      std::fprintf(stderr, "table7: %s\n", ours.status().to_string().c_str());
      return 1;
    }
    const Result<Mask> reference = to_mask(ours->volume);
    if (!reference.ok()) return 1;
    const auto one_d = run_method(Method::k1d, mesh, *reference, 1, *runs, *pin);
    const auto three_d = run_method(Method::k3d, mesh, *reference, 1, 1, *pin);
    const auto enclosed = run_method(Method::kVtkEnclosed, mesh, *reference, 1, 1, *pin);
    auto differing = [](const Result<MethodRun>& r) {
      return r.ok() ? std::to_string(r->vs_reference.differing) : std::string("n/a");
    };
    std::printf("| %zu | %zu | %lld | %lld | %s | %s | %s | %s | %s |\n", mesh.triangles.size(),
                mesh.vertices_mm.size(), (long long)grid->voxel_count(), (long long)voxel_count(ours->volume),
                time_cell(one_d).c_str(), time_cell(three_d).c_str(), time_cell(enclosed).c_str(),
                differing(three_d).c_str(), differing(enclosed).c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace soiq::bench
