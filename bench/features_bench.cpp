#include "bench/features_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bench/clock.h"
#include "bench/smoothed_structure.h"
#include "core/features/structure_features.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/support/simulated_models.h"

namespace soiq::bench {

namespace {

struct Row {
  std::string name;
  size_t triangles = 0;  // of the stored surface; 0 for a mask
  int64_t voxels = 0;
  std::optional<double> conversion_ms;
  std::map<std::string, double> part_ms;  // best per part
  double features_ms = 1e300;             // best total of structure_features
  size_t feature_count = 0;
  // Both again with two threads (simulated models only).
  std::optional<double> conversion_2_ms, features_2_ms;
  // Every shape feature but the two convex-hull densities (so no hull: the diameter alone), one
  // thread (simulated and smoothed surfaces only).
  std::optional<double> shape_no_hull_ms;
};

// Folds "resample PET inside" and the like into the part's kind, so rows share columns; the
// intensity-weighted centroid counts as an intensity feature.
std::string part_kind(const std::string& part) {
  if (part.rfind("centre of mass shift", 0) == 0) return "intensity";
  for (const char* kind : {"resample", "intensity", "region"}) {
    if (part.rfind(kind, 0) == 0) return kind;
  }
  return part;
}

Status measure(Row& row, const StructureInput& input, const FeatureRequest& request, int runs) {
  row.voxels = voxel_count(input.volume);
  for (int r = 0; r < runs; ++r) {
    const auto t0 = Clock::now();
    SOIQ_ASSIGN_OR_RETURN(FeatureReport report, structure_features(input, request));
    row.features_ms = std::min(row.features_ms, ms_since(t0));
    row.feature_count = report.features.size();
    std::map<std::string, double> sums;
    for (const auto& [part, ms] : report.timings_ms) sums[part_kind(part)] += ms;
    for (const auto& [kind, ms] : sums) {
      row.part_ms[kind] = row.part_ms.count(kind) ? std::min(row.part_ms[kind], ms) : ms;
    }
  }
  return ok_status();
}

// A smooth synthetic intensity on the grid (a ramp plus a ripple), so intensity features have
// something to compute on the simulated models.
Image ramp_image(const ImageGeometry& g) {
  Image image;
  image.geometry = g;
  image.voxels.resize(size_t(g.voxel_count()));
  size_t n = 0;
  for (int64_t k = 0; k < g.dims[2]; ++k)
    for (int64_t j = 0; j < g.dims[1]; ++j)
      for (int64_t i = 0; i < g.dims[0]; ++i) image.voxels[n++] = float(i + 2 * j + 3 * k + ((i * j) % 7));
  return image;
}

// Moves every vertex by up to 0.05 mm along each axis (a fixed pseudo-random sequence): the
// surface then lies in general position, as smoothed or resampled meshes from other tools do,
// instead of on the half-voxel lattice of marching cubes.
TriangleMesh jittered(TriangleMesh mesh) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> offset(-0.05, 0.05);
  for (Vec3& p : mesh.vertices_mm) {
    for (double& x : p) x += offset(rng);
  }
  return mesh;
}

// SM1's shell and core regions of several radii, on the runs and by the distance transform, and
// the way region() takes by its cost model: that model's calibration, measured.
Status print_region_table(const std::string& dir, int runs) {
  const std::string base = dir + "/SM1";
  if (!std::filesystem::exists(base + "_S1.vtp")) return ok_status();
  SOIQ_ASSIGN_OR_RETURN(TriangleMesh mesh, read_mesh(base + "_S1.vtp"));
  SOIQ_ASSIGN_OR_RETURN(Image v1, read_image(base + "_V1.nii.gz"));
  SOIQ_ASSIGN_OR_RETURN(Voxelization v, voxelize_1d(mesh, v1.geometry));
  std::printf(
      "\nSM1's regions, best ms of %d, one thread: on the runs (ball dilation or erosion) and by the distance "
      "transform over the grown box; \"taken\" is the way `region` picks by its cost model.\n\n",
      runs);
  std::printf("| region | voxels | on the runs ms | transform ms | taken |\n|---|---:|---:|---:|---|\n");
  for (const RegionSpec& spec :
       {RegionSpec{RegionKind::kShell, 3}, RegionSpec{RegionKind::kShell, 5}, RegionSpec{RegionKind::kShell, 10},
        RegionSpec{RegionKind::kShell, 20}, RegionSpec{RegionKind::kCore, 3}, RegionSpec{RegionKind::kCore, 5},
        RegionSpec{RegionKind::kCore, 10}}) {
    double best[2] = {1e300, 1e300};
    int64_t voxels = 0;
    for (int r = 0; r < runs; ++r) {
      for (const RegionMethod method : {RegionMethod::kRuns, RegionMethod::kTransform}) {
        RegionOptions options;
        options.method = method;
        const auto t0 = Clock::now();
        SOIQ_ASSIGN_OR_RETURN(RunLengthVolume out, region(v.volume, spec, options));
        double& b = best[method == RegionMethod::kRuns ? 0 : 1];
        b = std::min(b, ms_since(t0));
        voxels = voxel_count(out);
      }
    }
    SOIQ_ASSIGN_OR_RETURN(const RegionMethod taken, cheapest_region_method(v.volume, spec));
    std::printf("| %s | %lld | %.1f | %.1f | %s |\n", region_name(spec).c_str(), (long long)voxels, best[0], best[1],
                taken == RegionMethod::kRuns ? "runs" : "transform");
  }
  return ok_status();
}

// One row of a stored surface: its conversion onto `grid` and every feature (inside and a 3 mm
// shell on a ramp image over the grid), with one thread and then two.
Status surface_row(const std::string& name, TriangleMesh mesh, const ImageGeometry& grid, int runs,
                   std::vector<Row>& rows) {
  const Image ramp = ramp_image(grid);
  Row row;
  row.name = name;
  row.triangles = mesh.triangles.size();
  VoxelizeOptions options;
  options.known_defects = mesh_defects(mesh);  // the defect check belongs to loading the mesh
  // Conversion and features interleaved run by run, so both see the same machine load.
  FeatureRequest request;
  request.images = {{"ramp", &ramp}};
  request.regions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 3}};
  double best = 1e300;
  StructureInput input;
  input.surface = std::make_shared<const TriangleMesh>(std::move(mesh));
  for (int r = 0; r < runs; ++r) {
    const auto t0 = Clock::now();
    SOIQ_ASSIGN_OR_RETURN(Voxelization out, voxelize_1d(*input.surface, grid, options));
    best = std::min(best, ms_since(t0));
    input.volume = std::move(out.volume);
    SOIQ_RETURN_IF_ERROR(measure(row, input, request, 1));
  }
  row.conversion_ms = best;
  FeatureRequest no_hull;
  for (const FeatureDef& f : feature_catalogue()) {
    if (f.family == FeatureFamily::kIntensity || f.needs.has(FeatureNeed::kConvexHull)) continue;
    no_hull.names.emplace_back(f.name);
    if (f.family == FeatureFamily::kSurface) no_hull.names.push_back("mask_" + std::string(f.name));
  }
  double best_no_hull = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = Clock::now();
    SOIQ_RETURN_IF_ERROR(structure_features(input, no_hull).status());
    best_no_hull = std::min(best_no_hull, ms_since(t0));
  }
  row.shape_no_hull_ms = best_no_hull;
  // Two threads for both: the conversion's slabs, and the independent feature parts at once.
  options.threads = request.threads = 2;
  double best_conversion = 1e300, best_features = 1e300;
  for (int r = 0; r < runs; ++r) {
    auto t0 = Clock::now();
    SOIQ_ASSIGN_OR_RETURN(Voxelization out, voxelize_1d(*input.surface, grid, options));
    best_conversion = std::min(best_conversion, ms_since(t0));
    input.volume = std::move(out.volume);
    t0 = Clock::now();
    SOIQ_RETURN_IF_ERROR(structure_features(input, request).status());
    best_features = std::min(best_features, ms_since(t0));
  }
  row.conversion_2_ms = best_conversion, row.features_2_ms = best_features;
  rows.push_back(std::move(row));
  return ok_status();
}

Status simulated_rows(const std::string& dir, int runs, std::vector<Row>& rows) {
  for (const SimModel& model : simulated_models()) {
    const std::string base = dir + "/" + model.name;
    if (!std::filesystem::exists(base + "_S1.vtp")) continue;
    SOIQ_ASSIGN_OR_RETURN(TriangleMesh lattice_mesh, read_mesh(base + "_S1.vtp"));
    SOIQ_ASSIGN_OR_RETURN(Image v1, read_image(base + "_V1.nii.gz"));
    SOIQ_RETURN_IF_ERROR(surface_row(model.name, lattice_mesh, v1.geometry, runs, rows));
    // SM1 also with its surface in general position (one extra row).
    if (model.name == "SM1") {
      SOIQ_RETURN_IF_ERROR(
          surface_row(model.name + " S1 jittered 0.05 mm", jittered(lattice_mesh), v1.geometry, runs, rows));
    }
    std::fprintf(stderr, "features: %s done\n", model.name.c_str());
  }
  return ok_status();
}

// A real structure as other tools export it: STS_002's tumour (its CT mask), smoothed and refined
// to at least 100k triangles (smoothed_structure.h), converted on a 1 mm grid around it.
Status smoothed_row(const std::string& sts_dir, int runs, std::vector<Row>& rows) {
  const std::string path = sts_dir + "/STS_002/CT_mask.nii.gz";
  if (!std::filesystem::exists(path)) return ok_status();
  SOIQ_ASSIGN_OR_RETURN(const Image image, read_image(path));
  SOIQ_ASSIGN_OR_RETURN(TriangleMesh mesh, smoothed_structure(mask_from_image(image), 100000));
  SOIQ_ASSIGN_OR_RETURN(const ImageGeometry grid, grid_around(mesh, Vec3{1, 1, 1}, 2));
  return surface_row("STS_002 tumour, smoothed surface", std::move(mesh), grid, runs, rows);
}

Status sts_rows(const std::string& dir, int runs, std::vector<Row>& rows) {
  std::vector<std::string> patients;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (std::filesystem::exists(entry.path() / "CT_mask.nii.gz")) patients.push_back(entry.path().filename());
  }
  std::sort(patients.begin(), patients.end());
  for (const std::string& patient : patients) {
    const std::string base = dir + "/" + patient;
    SOIQ_ASSIGN_OR_RETURN(Image mask, read_image(base + "/CT_mask.nii.gz"));
    std::optional<Image> pet;
    if (std::filesystem::exists(base + "/PET_image.nii.gz")) {
      SOIQ_ASSIGN_OR_RETURN(Image image, read_image(base + "/PET_image.nii.gz"));
      pet = std::move(image);
    }
    Row row;
    row.name = patient + " CT mask" + (pet ? " + PET" : "");
    FeatureRequest request;
    if (pet) {
      request.images = {{"PET", &*pet}};
      request.regions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 5}};
    }
    SOIQ_RETURN_IF_ERROR(measure(row, StructureInput{from_mask(mask_from_image(mask)), nullptr}, request, runs));
    rows.push_back(std::move(row));
  }
  return ok_status();
}

}  // namespace

int run_features_bench(const CliArgs& args) {
  const std::string models = args.get("--models", "");
  const std::string sts = args.get("--sts", "");
  const Result<int> runs = args.get_int("--runs", 3);
  if ((models.empty() && sts.empty()) || !runs.ok() || *runs < 1) {
    std::fprintf(stderr, "usage: soiq-bench features --models DIR [--sts DIR] [--runs N]\n");
    return 2;
  }
  std::vector<Row> rows;
  Status s = models.empty() ? ok_status() : simulated_rows(models, *runs, rows);
  if (s.ok() && !sts.empty()) s = smoothed_row(sts, *runs, rows);
  if (s.ok() && !sts.empty()) s = sts_rows(sts, *runs, rows);
  if (!s.ok()) {
    std::fprintf(stderr, "soiq-bench features: %s\n", s.to_string().c_str());
    return 1;
  }
  const std::vector<std::pair<std::string, std::string>> columns = {{"volume shape", "volume"},
                                                                    {"mask surface sweep", "mask sweep"},
                                                                    {"surface shape", "stored surface"},
                                                                    {"mask surface shape", "mask surface"},
                                                                    {"2d diameters", "2D diameters"},
                                                                    {"region", "regions"},
                                                                    {"resample", "resample"},
                                                                    {"intensity", "intensity"}};
  std::printf(
      "Best ms of %d runs per part; \"features\" is the whole structure_features call (all features); \"shape\" "
      "the sum of the parts that need no image (volume, mask sweep, stored surface, mask surface, 2D diameters); "
      "conversion and features run interleaved, one after the other in each run.\n\n",
      *runs);
  // The parts that need no image: every shape feature.
  const std::vector<std::string> shape_parts = {"volume shape", "mask surface sweep", "surface shape",
                                                "mask surface shape", "2d diameters"};
  std::printf("| structure | triangles | voxels | conversion ms | features ms | shape ms | features |");
  for (const auto& c : columns) std::printf(" %s ms |", c.second.c_str());
  std::printf("\n|---|---:|---:|---:|---:|---:|---:|");
  for (size_t c = 0; c < columns.size(); ++c) std::printf("---:|");
  std::printf("\n");
  for (const Row& r : rows) {
    char conversion[32] = "-";
    if (r.conversion_ms) std::snprintf(conversion, sizeof conversion, "%.1f", *r.conversion_ms);
    double shape_ms = 0;
    for (const std::string& part : shape_parts) {
      const auto it = r.part_ms.find(part);
      if (it != r.part_ms.end()) shape_ms += it->second;
    }
    std::printf("| %s | %s | %lld | %s | %.1f | %.1f | %zu |", r.name.c_str(),
                r.triangles ? std::to_string(r.triangles).c_str() : "-", (long long)r.voxels, conversion, r.features_ms,
                shape_ms, r.feature_count);
    for (const auto& c : columns) {
      const auto it = r.part_ms.find(c.first);
      if (it == r.part_ms.end()) {
        std::printf(" - |");
      } else {
        std::printf(" %.1f |", it->second);
      }
    }
    std::printf("\n");
  }
  std::printf(
      "\nThe same with two threads (best of %d): the conversion splits its slabs, structure_features runs its "
      "independent parts (volume, stored surface, mask surface, each region with its intensities) at once.\n\n",
      *runs);
  std::printf(
      "| structure | conversion ms, 1 thread | conversion ms, 2 threads | features ms, 1 thread | "
      "features ms, 2 threads |\n|---|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    if (!r.conversion_2_ms) continue;
    std::printf("| %s | %.1f | %.1f | %.1f | %.1f |\n", r.name.c_str(), *r.conversion_ms, *r.conversion_2_ms,
                r.features_ms, *r.features_2_ms);
  }
  std::printf(
      "\nOne thread, as ratios to the conversion: \"shape\" and \"features\" from the first table; \"shape, no "
      "hull\" asks every shape feature but the two convex-hull densities, so the exact hull is skipped and the "
      "maximum 3D diameter is found without it (surface_shape.h, HullPart).\n\n");
  std::printf(
      "| structure | conversion ms | features / conversion | shape / conversion | shape, no hull ms | shape, no "
      "hull / conversion |\n|---|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    if (!r.conversion_ms || !r.shape_no_hull_ms) continue;
    double shape_ms = 0;
    for (const std::string& part : shape_parts) {
      const auto it = r.part_ms.find(part);
      if (it != r.part_ms.end()) shape_ms += it->second;
    }
    const double c = *r.conversion_ms;
    std::printf("| %s | %.1f | %.1fx | %.1fx | %.1f | %.1fx |\n", r.name.c_str(), c, r.features_ms / c, shape_ms / c,
                *r.shape_no_hull_ms, *r.shape_no_hull_ms / c);
  }
  if (!models.empty()) {
    if (const Status t = print_region_table(models, *runs); !t.ok()) {
      std::fprintf(stderr, "soiq-bench features: %s\n", t.to_string().c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace soiq::bench
