#include "bench/scaling.h"

#include <cstdio>

#include "bench/method_run.h"
#include "core/base/run_length_volume.h"
#include "core/geometry/primitives.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::bench {

int run_scaling(const CliArgs& args) {
  const Result<int> runs = args.get_int("--runs", 3);
  const Result<int> threads = args.get_int("--threads", 2);
  const Result<int> pin = args.get_int("--pin", 0);
  if (!runs.ok() || !threads.ok() || !pin.ok() || *threads < 1) {
    std::fprintf(stderr, "usage: soiq-bench scaling [--runs N] [--threads T] [--pin CPU]\n");
    return 2;
  }
  std::printf("UV spheres, radius 40 mm, 2-voxel margin; best ms of up to %d runs (dense uint8 mask included)\n\n",
              *runs);
  std::printf(
      "| triangles | spacing mm | grid | inside | 1d ms | 1d x%d ms | vtk-stencil ms | vtk-stencil differing |\n"
      "|---:|---:|---|---:|---:|---:|---:|---:|\n",
      *threads);
  for (int64_t triangles : {1'000, 10'000, 100'000, 1'000'000}) {
    const TriangleMesh mesh = uv_sphere_with_triangles({0.3, -0.2, 0.1}, 40, triangles);
    for (double spacing : {1.0, 0.25}) {
      const Result<ImageGeometry> grid = grid_around(mesh, {spacing, spacing, spacing}, 2);
      if (!grid.ok()) return 1;
      const auto ours = voxelize_1d(mesh, *grid);
      if (!ours.ok()) {
        std::fprintf(stderr, "scaling: %s\n", ours.status().to_string().c_str());
        return 1;
      }
      const Result<Mask> reference = to_mask(ours->volume);
      if (!reference.ok()) return 1;
      const auto one = run_method(Method::k1d, mesh, *reference, 1, *runs, *pin);
      const auto many = run_method(Method::k1d, mesh, *reference, *threads, *runs, *pin);
      const auto vtk = run_method(Method::kVtkStencil, mesh, *reference, 1, *runs, *pin);
      std::printf("| %zu | %g | %lldx%lldx%lld | %lld | %s | %s | %s | %s |\n", mesh.triangles.size(), spacing,
                  (long long)grid->dims[0], (long long)grid->dims[1], (long long)grid->dims[2],
                  (long long)voxel_count(ours->volume), time_cell(one).c_str(), time_cell(many).c_str(),
                  time_cell(vtk).c_str(), vtk.ok() ? std::to_string(vtk->vs_reference.differing).c_str() : "n/a");
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace soiq::bench
