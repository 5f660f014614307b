#include "bench/table5.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/method_run.h"
#include "bench/simgen.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"

namespace soiq::bench {

namespace {

struct Row {
  std::string model;
  size_t triangles = 0;
  int64_t voxels = 0;
  std::vector<Result<MethodRun>> cells;
};

}  // namespace

int run_table5(const CliArgs& args) {
  const std::string dir = args.get("--models", "");
  const Result<int> runs = args.get_int("--runs", 5);
  const Result<int> threads = args.get_int("--threads", 2);
  const Result<int> pin = args.get_int("--pin", 0);
  if (dir.empty() || !runs.ok() || !threads.ok() || !pin.ok() || *threads < 1) {
    std::fprintf(stderr, "usage: soiq-bench table5 --models DIR [--runs N] [--threads T] [--pin CPU]\n");
    return 2;
  }
  struct Column {
    Method method;
    int threads;
    std::string title;
  };
  const std::vector<Column> columns = {
      {Method::k1d, 1, "1d"},   {Method::k1d, *threads, "1d x" + std::to_string(*threads)},
      {Method::k2d, 1, "2d"},   {Method::kVtkStencil, 1, "vtk-stencil"},
      {Method::kItk, 1, "itk"},
  };

  std::vector<Row> rows;
  for (const SimModel& model : simulated_models()) {
    const std::string base = dir + "/" + model.name;
    if (!std::filesystem::exists(base + "_S1.vtp")) continue;
    const Result<TriangleMesh> mesh = read_mesh(base + "_S1.vtp");
    const Result<Image> image = read_image(base + "_V1.nii.gz");
    if (!mesh.ok() || !image.ok()) {
      std::fprintf(stderr, "table5: %s: %s\n", model.name.c_str(),
                   (!mesh.ok() ? mesh.status() : image.status()).to_string().c_str());
      return 1;
    }
    const Mask v1 = mask_from_image(*image);
    Row row{model.name, mesh->triangles.size(), 0, {}};
    for (uint8_t v : v1.voxels) row.voxels += v;
    for (const Column& c : columns) {
      if (!method_available(c.method)) {
        row.cells.push_back(unimplemented("not built"));
        continue;
      }
      row.cells.push_back(run_method(c.method, *mesh, v1, c.threads, *runs, *pin));
      if (!row.cells.back().ok()) {
        std::fprintf(stderr, "table5: %s %s: %s\n", model.name.c_str(), c.title.c_str(),
                     row.cells.back().status().to_string().c_str());
      }
    }
    std::fprintf(stderr, "table5: %s done\n", model.name.c_str());
    rows.push_back(std::move(row));
  }

  std::printf("Conversion time, median ms of up to %d runs (grid from SMn_V1, mesh SMn_S1 = marching cubes of V1)\n\n",
              *runs);
  std::printf("| model | triangles | V1 voxels |");
  for (const Column& c : columns) std::printf(" %s ms |", c.title.c_str());
  std::printf("\n|---|---:|---:|");
  for (size_t c = 0; c < columns.size(); ++c) std::printf("---:|");
  std::printf("\n");
  for (const Row& r : rows) {
    std::printf("| %s | %zu | %lld |", r.model.c_str(), r.triangles, (long long)r.voxels);
    for (const auto& cell : r.cells) std::printf(" %s |", time_cell(cell).c_str());
    std::printf("\n");
  }
  std::printf("\nIoU against V1 (differing voxels)\n\n| model |");
  for (const Column& c : columns) std::printf(" %s |", c.title.c_str());
  std::printf("\n|---|");
  for (size_t c = 0; c < columns.size(); ++c) std::printf("---:|");
  std::printf("\n");
  for (const Row& r : rows) {
    std::printf("| %s |", r.model.c_str());
    for (const auto& cell : r.cells) std::printf(" %s |", agreement_cell(cell).c_str());
    std::printf("\n");
  }
  return 0;
}

}  // namespace soiq::bench
