#include "bench/convert_bench.h"

#include <cstdio>
#include <optional>

#include "bench/conversion.h"
#include "bench/cpu_affinity.h"
#include "bench/timing.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/io/write_image.h"

namespace soiq::bench {

namespace {

int fail(const Status& s) {
  std::fprintf(stderr, "convert: %s\n", s.to_string().c_str());
  return s.code() == StatusCode::kInvalidArgument ? 2 : 1;
}

// JSON string escaping for paths.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

int run_convert(const CliArgs& args) {
  if (args.positional.size() != 1 || !args.has("--reference")) {
    std::fprintf(stderr,
                 "usage: soiq-bench convert MESH --reference IMAGE --method 1d|2d|3d|vtk-stencil|"
                 "vtk-enclosed|itk|cgal|openvdb [--runs N] [--threads T] [--pin CPU] [--json] [-o OUT]\n");
    return 2;
  }
  const Result<Method> method = parse_method(args.get("--method", "1d"));
  if (!method.ok()) return fail(method.status());
  const Result<int> runs = args.get_int("--runs", 5);
  const Result<int> threads = args.get_int("--threads", 1);
  const Result<int> pin = args.get_int("--pin", -1);
  if (!runs.ok()) return fail(runs.status());
  if (!threads.ok() || *threads < 1) return fail(invalid_argument("--threads must be an integer >= 1"));
  if (!pin.ok()) return fail(pin.status());

  const std::string mesh_path = args.positional[0], image_path = args.get("--reference", "");
  const Result<TriangleMesh> mesh = read_mesh(mesh_path);
  if (!mesh.ok()) return fail(mesh.status());
  const Result<Image> image = read_image(image_path);
  if (!image.ok()) return fail(image.status());
  const ImageGeometry geometry = image->geometry;

  const Result<Conversion> conversion = prepare_conversion(*method, *mesh, geometry, *threads);
  if (!conversion.ok()) return fail(conversion.status());
  std::optional<ScopedAffinity> affinity;
  if (*threads == 1) affinity.emplace(*pin);
  const Result<Timed> timed = time_conversion(*conversion, *runs);
  affinity.reset();
  if (!timed.ok()) return fail(timed.status());

  int64_t inside = 0;
  for (uint8_t v : timed->mask.voxels) inside += v != 0;
  if (args.has("-o")) {
    const Status st = write_mask(timed->mask, args.get("-o", ""));
    if (!st.ok()) return fail(st);
  }
  const auto& d = geometry.dims;
  if (args.has("--json")) {
    std::printf(
        "{\"mesh\": %s, \"reference\": %s, \"method\": \"%s\", \"threads\": %d, \"runs\": %d, "
        "\"triangles\": %zu, \"dims\": [%lld, %lld, %lld], \"min_ms\": %.3f, \"median_ms\": %.3f, "
        "\"voxels_inside\": %lld}\n",
        quoted(mesh_path).c_str(), quoted(image_path).c_str(), method_name(*method), *threads, timed->runs,
        mesh->triangles.size(), (long long)d[0], (long long)d[1], (long long)d[2], timed->min_ms, timed->median_ms,
        (long long)inside);
  } else {
    std::printf("%s: %zu triangles on %s, %d runs x %d threads: min %.3f ms, median %.3f ms, %lld voxels inside\n",
                method_name(*method), mesh->triangles.size(), describe(geometry).c_str(), timed->runs, *threads,
                timed->min_ms, timed->median_ms, (long long)inside);
  }
  return 0;
}

}  // namespace soiq::bench
