#include "bench/simgen.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/io/marching_cubes.h"
#include "core/io/write_image.h"
#include "core/io/write_mesh.h"
#include "tests/support/simulated_models.h"

namespace soiq::bench {

namespace {

std::string join_r3(const SimModel& m) {
  if (m.stripe_r3_mm.empty()) return "-";
  std::string out;
  char buf[32];
  for (double r : m.stripe_r3_mm) {
    std::snprintf(buf, sizeof buf, "%s%.2f", out.empty() ? "" : ",", r);
    out += buf;
  }
  return out;
}

}  // namespace

int run_simgen(const CliArgs& args) {
  const std::string out = args.get("--out", "");
  if (out.empty()) {
    std::fprintf(stderr, "simgen: --out DIR is required\n");
    return 2;
  }
  const Result<double> spacing = args.get_double("--spacing", 1.0);
  if (!spacing.ok() || !(*spacing > 0)) {
    std::fprintf(stderr, "simgen: --spacing must be a number > 0\n");
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  std::ofstream tsv(out + "/models.tsv");
  if (!tsv) {
    std::fprintf(stderr, "simgen: cannot write %s/models.tsv\n", out.c_str());
    return 1;
  }
  tsv << "name\tR1_mm\tR2_mm\tw\tR3_mm\tspacing_mm\tdims\ttriangles\tvoxels\n";
  for (const SimModel& model : simulated_models()) {
    const Mask v1 = simulated_volume(model, *spacing);
    int64_t voxels = 0;
    for (uint8_t v : v1.voxels) voxels += v;
    const std::string base = out + "/" + model.name;
    Status st = write_mask(v1, base + "_V1.nii.gz");
    if (!st.ok()) {
      std::fprintf(stderr, "simgen: %s\n", st.to_string().c_str());
      return 1;
    }
    const Result<TriangleMesh> s1 = marching_cubes(v1);
    if (!s1.ok()) {
      std::fprintf(stderr, "simgen: %s\n", s1.status().to_string().c_str());
      return 1;
    }
    st = write_mesh(*s1, base + "_S1.vtp");
    if (!st.ok()) {
      std::fprintf(stderr, "simgen: %s\n", st.to_string().c_str());
      return 1;
    }
    const auto& d = v1.geometry.dims;
    tsv << model.name << '\t' << model.r1_mm << '\t' << model.r2_mm << '\t' << model.stripe_r3_mm.size() << '\t'
        << join_r3(model) << '\t' << *spacing << '\t' << d[0] << 'x' << d[1] << 'x' << d[2] << '\t'
        << s1->triangles.size() << '\t' << voxels << '\n';
    std::printf("%s: %lldx%lldx%lld, %zu triangles, %lld voxels\n", model.name.c_str(), (long long)d[0],
                (long long)d[1], (long long)d[2], s1->triangles.size(), (long long)voxels);
  }
  return 0;
}

}  // namespace soiq::bench
