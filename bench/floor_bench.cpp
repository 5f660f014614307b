#include "bench/floor_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/conversion.h"
#include "bench/cpu_affinity.h"
#include "bench/scanline_floor.h"
#include "core/base/cpu_level.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"

namespace soiq::bench {

namespace {

int fail(const Status& s) {
  std::fprintf(stderr, "floor: %s\n", s.to_string().c_str());
  return s.code() == StatusCode::kInvalidArgument ? 2 : 1;
}

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    if (!name.empty()) out.push_back(name);
  }
  return out;
}

template <typename F>
double time_ms(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int run_floor_bench(const CliArgs& args) {
  if (!args.has("--models")) {
    std::fprintf(stderr, "usage: soiq-bench floor --models DIR [--names SM1,SM6,SM11] [--runs N] [--pin CPU]\n");
    return 2;
  }
  const Result<int> runs = args.get_int("--runs", 11);
  const Result<int> pin = args.get_int("--pin", 0);
  if (!runs.ok() || *runs < 1) return fail(invalid_argument("--runs must be an integer >= 1"));
  if (!pin.ok()) return fail(pin.status());
  const std::string dir = args.get("--models", "");
  std::printf("| model | triangles | lattice points | floor ms | 1d ms | 1d / floor |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  for (const std::string& name : split_names(args.get("--names", "SM1,SM6,SM11"))) {
    const Result<TriangleMesh> mesh = read_mesh(dir + "/" + name + "_S1.vtp");
    if (!mesh.ok()) return fail(mesh.status());
    const Result<Image> image = read_image(dir + "/" + name + "_V1.nii.gz");
    if (!image.ok()) return fail(image.status());
    const Result<Conversion> one_d = prepare_conversion(Method::k1d, *mesh, image->geometry, 1);
    if (!one_d.ok()) return fail(one_d.status());
    double floor_ms = 1e300, one_d_ms = 1e300;
    int64_t points = 0;
    ScopedAffinity affinity(*pin);
    for (int r = 0; r < *runs; ++r) {
      // Each run's output is released outside the timed region, as time_conversion does.
      std::optional<FloorRun> floor;
      floor_ms = std::min(floor_ms, time_ms([&] { floor = scanline_floor(*mesh, image->geometry); }));
      points = floor->lattice_points;
      floor.reset();
      std::optional<Result<Mask>> mask;
      one_d_ms = std::min(one_d_ms, time_ms([&] { mask = (*one_d)(); }));
      if (!mask->ok()) return fail(mask->status());
    }
    std::printf("| %s | %zu | %lld | %.3f | %.3f | %.2fx |\n", name.c_str(), mesh->triangles.size(), (long long)points,
                floor_ms, one_d_ms, one_d_ms / floor_ms);
  }
  std::printf("\n(%d runs each, alternating, one thread pinned to CPU %d; kernels at %s)\n", *runs, *pin,
              std::string(cpu_level_name(cpu_level())).c_str());
  return 0;
}

}  // namespace soiq::bench
