#include "bench/coverage_bench.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <vector>

#include "bench/clock.h"
#include "bench/coverage_accuracy.h"
#include "bench/cpu_affinity.h"
#include "core/geometry/mesh_defects.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq::bench {

namespace {

int fail(const Status& s) {
  std::fprintf(stderr, "coverage: %s\n", s.to_string().c_str());
  return 1;
}

constexpr int kLines[] = {1, 2, 4, 8};

}  // namespace

int run_coverage_bench(const CliArgs& args) {
  if (!args.has("--models")) {
    std::fprintf(stderr, "usage: soiq-bench coverage --models DIR [--sts DIR] [--runs N] [--pin CPU]\n");
    return 2;
  }
  const Result<int> runs = args.get_int("--runs", 9);
  const Result<int> pin = args.get_int("--pin", -1);
  if (!runs.ok() || *runs < 1) return fail(invalid_argument("--runs must be an integer >= 1"));
  if (!pin.ok()) return fail(pin.status());
  const std::string dir = args.get("--models", "");
  std::optional<ScopedAffinity> affinity;
  affinity.emplace(*pin);

  std::printf("| model | triangles | grid | plain 1D ms |");
  for (int n : kLines) std::printf(" n=%d ms (x plain) |", n);
  std::printf(" partly covered voxels n=4 |\n|---|---:|---|---:|");
  for (int n : kLines) std::printf("---:|"), (void)n;
  std::printf("---:|\n");
  for (const char* model : {"SM1", "SM6", "SM11"}) {
    const Result<TriangleMesh> mesh = read_mesh(dir + "/" + model + "_S1.vtp");
    if (!mesh.ok()) return fail(mesh.status());
    const Result<Image> reference = read_image(dir + "/" + model + "_V1.nii.gz");
    if (!reference.ok()) return fail(reference.status());
    const ImageGeometry& g = reference->geometry;
    const MeshDefects defects = mesh_defects(*mesh);
    VoxelizeOptions plain;
    plain.known_defects = defects;
    std::vector<double> best(1 + std::size(kLines), 1e300);
    size_t partial = 0;
    // Interleaved: one run of every variant per round, the least of the rounds kept.
    for (int r = 0; r < *runs; ++r) {
      auto start = Clock::now();
      const auto v = voxelize_1d(*mesh, g, plain);
      best[0] = std::min(best[0], ms_since(start));
      if (!v.ok()) return fail(v.status());
      for (size_t c = 0; c < std::size(kLines); ++c) {
        CoverageOptions o;
        o.lines_per_voxel = kLines[c];
        o.known_defects = defects;
        start = Clock::now();
        const auto cv = coverage_1d(*mesh, g, o);
        best[c + 1] = std::min(best[c + 1], ms_since(start));
        if (!cv.ok()) return fail(cv.status());
        if (kLines[c] == 4) partial = cv->partial.size();
      }
    }
    std::printf("| %s | %zu | %lldx%lldx%lld | %.2f |", model, mesh->triangles.size(), (long long)g.dims[0],
                (long long)g.dims[1], (long long)g.dims[2], best[0]);
    for (size_t c = 0; c < std::size(kLines); ++c) std::printf(" %.2f (%.2fx) |", best[c + 1], best[c + 1] / best[0]);
    std::printf(" %zu |\n", partial);
  }
  std::printf("\nLeast of %d interleaved rounds, one thread%s.\n", *runs,
              affinity->pinned() ? " pinned to one CPU" : " (unpinned)");
  affinity.reset();
  std::printf("\nSum of fractions x voxel volume against the exact volume of the polyhedron:\n\n");
  if (Status s = print_volume_accuracy(); !s.ok()) return fail(s);
  std::printf(
      "\nA 1 cm lesion (radius 5 mm) at 64 sub-voxel positions, the image its uptake field sampled at the "
      "voxel centres: error of the mean uptake against the field's exact mean over the lesion (mean and "
      "standard deviation over the positions), and mean |error| of the volume against the mesh's:\n\n");
  if (Status s = print_lesion_accuracy(); !s.ok()) return fail(s);
  if (args.has("--sts")) {
    std::printf("\nThe STS tumours on their PET series:\n\n");
    if (Status s = print_sts_pet_uptake(args.get("--sts", "")); !s.ok()) return fail(s);
  }
  return 0;
}

}  // namespace soiq::bench
