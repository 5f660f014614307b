#include "bench/table5.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/method_run.h"
#include "core/geometry/mesh_defects.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "tests/support/simulated_models.h"

namespace soiq::bench {

namespace {

struct Row {
  std::string model;
  size_t triangles = 0;
  int64_t voxels = 0;
  double check_ms = 0;  // mesh_defects, best of the runs
  std::vector<Result<MethodRun>> cells;
};

struct Column {
  Method method;
  int threads;
  std::string title;
  std::string ratio_title;  // a peer's "x / 1d" speed-up column; empty for ours
};

// The table's method columns: ours, then VTK and each optional peer this soiq-bench was built with
// (one not built would only be a column of n/a; print_times names those).
std::vector<Column> table5_columns(int threads) {
  std::vector<Column> columns = {
      {Method::k1d, 1, "1d", ""},
      {Method::k1d, threads, "1d x" + std::to_string(threads), ""},
      {Method::k2d, 1, "2d", ""},
      {Method::kVtkStencil, 1, "vtk-stencil", "vtk / 1d"},
  };
  for (Method m : {Method::kItk, Method::kCgal, Method::kOpenVdb}) {
    if (method_available(m)) columns.push_back({m, 1, method_name(m), std::string(method_name(m)) + " / 1d"});
  }
  return columns;
}

// Best ms of `runs` mesh defect checks, the cost a conversion pays once when a mesh is loaded;
// warns on stderr when the mesh is not closed, and goes on: the table still shows what each method
// makes of it.
double best_check_ms(const TriangleMesh& mesh, int runs, const std::string& model) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const MeshDefects d = mesh_defects(mesh);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, ms);
    if (!d.closed()) std::fprintf(stderr, "table5: %s is not closed\n", model.c_str());
  }
  return best;
}

// One model's row: its S1 mesh converted onto the grid of its V1 image by every column's method,
// interleaved so that all see the same machine. A method that was not built, or failed, gets its
// reason in the cell (and on stderr); only a model that cannot be read is an error.
Result<Row> measure_model(const std::string& model, const std::string& base, const std::vector<Column>& columns,
                          int runs, int pin) {
  const Result<TriangleMesh> mesh = read_mesh(base + "_S1.vtp");
  const Result<Image> image = read_image(base + "_V1.nii.gz");
  if (!mesh.ok()) return mesh.status();
  if (!image.ok()) return image.status();
  const Mask v1 = mask_from_image(*image);
  Row row{model, mesh->triangles.size(), 0, 0, {}};
  for (uint8_t v : v1.voxels) row.voxels += v;
  row.check_ms = best_check_ms(*mesh, runs, model);
  std::vector<MethodSpec> specs;
  for (const Column& c : columns) specs.push_back({c.method, c.threads});
  row.cells = run_methods_interleaved(specs, *mesh, v1, runs, pin);
  for (size_t c = 0; c < columns.size(); ++c) {
    if (!method_available(columns[c].method)) row.cells[c] = unimplemented("not built");
    if (!row.cells[c].ok()) {
      std::fprintf(stderr, "table5: %s %s: %s\n", model.c_str(), columns[c].title.c_str(),
                   row.cells[c].status().to_string().c_str());
    }
  }
  return row;
}

// "num / den" of two best times with two decimals, or "n/a" when either is missing.
std::string ratio(const Result<MethodRun>& num, const Result<MethodRun>& den) {
  char buf[32];
  if (!num.ok() || !den.ok() || den->timed.min_ms <= 0) return std::string("n/a");
  // Two decimals: the targets (10x, 50x, 1.6x) are thresholds, and 1.55 must not read as 1.6.
  std::snprintf(buf, sizeof buf, "%.2fx", num->timed.min_ms / den->timed.min_ms);
  return std::string(buf);
}

// The times table: what was measured and how, then one line per model with the speed-ups.
void print_times(const std::vector<Row>& rows, const std::vector<Column>& columns, int runs, int threads) {
  std::printf(
      "Conversion time, best ms of %d runs taken in rounds, one run of every method per round, so that all methods "
      "see\n"
      "the same machine (grid from SMn_V1, mesh SMn_S1 = marching cubes of V1). \"check\" is the\n"
      "mesh defect check (closedness, orientation) done once when a mesh is loaded; the speed-ups compare 1d on one\n"
      "thread with the peers on one thread, and 1d on %d threads with 1d on one.\n",
      runs, threads);
  std::string missing;
  for (Method m : {Method::kItk, Method::kCgal, Method::kOpenVdb}) {
    if (!method_available(m)) missing += std::string(missing.empty() ? "" : ", ") + method_name(m);
  }
  if (!missing.empty()) std::printf("Peers not in this build of soiq-bench: %s.\n", missing.c_str());
  std::printf("\n| model | triangles | V1 voxels | check ms |");
  size_t ratios = 0;
  for (const Column& c : columns) std::printf(" %s ms |", c.title.c_str());
  for (const Column& c : columns) {
    if (c.ratio_title.empty()) continue;
    std::printf(" %s |", c.ratio_title.c_str());
    ++ratios;
  }
  std::printf(" 1d x%d speed-up |\n|---|---:|---:|---:|", threads);
  for (size_t c = 0; c < columns.size() + ratios + 1; ++c) std::printf("---:|");
  std::printf("\n");
  for (const Row& r : rows) {
    std::printf("| %s | %zu | %lld | %.1f |", r.model.c_str(), r.triangles, (long long)r.voxels, r.check_ms);
    for (const auto& cell : r.cells) std::printf(" %s |", time_cell(cell).c_str());
    // Columns 0 and 1 are 1d on one thread and on `threads`.
    for (size_t c = 0; c < columns.size(); ++c) {
      if (!columns[c].ratio_title.empty()) std::printf(" %s |", ratio(r.cells[c], r.cells[0]).c_str());
    }
    std::printf(" %s |\n", ratio(r.cells[0], r.cells[1]).c_str());
  }
}

// The agreement table: each method's mask against V1 (IoU and differing voxels).
void print_agreement(const std::vector<Row>& rows, const std::vector<Column>& columns) {
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
}

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
  const std::vector<Column> columns = table5_columns(*threads);
  std::vector<Row> rows;
  for (const SimModel& model : simulated_models()) {
    const std::string base = dir + "/" + model.name;
    if (!std::filesystem::exists(base + "_S1.vtp")) continue;
    Result<Row> row = measure_model(model.name, base, columns, *runs, *pin);
    if (!row.ok()) {
      std::fprintf(stderr, "table5: %s: %s\n", model.name.c_str(), row.status().to_string().c_str());
      return 1;
    }
    std::fprintf(stderr, "table5: %s done\n", model.name.c_str());
    rows.push_back(std::move(*row));
  }
  print_times(rows, columns, *runs, *threads);
  print_agreement(rows, columns);
  return 0;
}

}  // namespace soiq::bench
