#include "core/features/structure_features.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>

#include "core/base/run_tasks.h"
#include "core/features/centre_of_mass_shift.h"
#include "core/features/feature_catalogue.h"
#include "core/features/intensity_features.h"
#include "core/features/marching_cubes_table.h"
#include "core/features/mask_maximum_2d_diameters.h"
#include "core/features/mask_surface_mesh.h"
#include "core/features/mask_surface_shape.h"
#include "core/features/mask_surface_sweep.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/features/surface_shape.h"
#include "core/features/weighted_intensity.h"
#include "core/voxelize/coverage_1d.h"

namespace soiq {

namespace {

bool contains(const std::vector<std::string>& list, std::string_view name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// Times one part of the work under its name.
class PartTimer {
 public:
  explicit PartTimer(FeatureReport& report) : report_(report) {}
  template <typename F>
  auto run(const std::string& part, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    auto result = f();
    report_.timings_ms.emplace_back(
        part, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    return result;
  }

 private:
  FeatureReport& report_;
};

// What a call asks for, shared by its sections.
struct Ask {
  const StructureInput& input;
  const FeatureRequest& request;
  const CoverageVolume* coverage = nullptr;  // when a coverage-weighted feature is asked
  // No names: every feature but the coverage-weighted ones, which are computed only when named.
  bool wanted(std::string_view n) const {
    if (request.names.empty()) return !is_weighted(n);
    return contains(request.names, n);
  }
  static bool is_weighted(std::string_view n) {
    const auto& w = weighted_feature_names();
    return std::find(w.begin(), w.end(), n) != w.end();
  }
  // Any feature of `family` wanted under `prefix` ("mask_" for the mask surface's beside a stored one).
  bool any_wanted(FeatureFamily family, std::string_view prefix = "") const {
    for (const FeatureDef& f : feature_catalogue())
      if (f.family == family && wanted(std::string(prefix) + std::string(f.name))) return true;
    return false;
  }
  // Any feature of `family` wanted under `prefix` whose catalogue entry needs `need`.
  bool any_wanted_needing(FeatureFamily family, FeatureNeed need, std::string_view prefix = "") const {
    for (const FeatureDef& f : feature_catalogue())
      if (f.family == family && f.needs.has(need) && wanted(std::string(prefix) + std::string(f.name))) return true;
    return false;
  }
  // The hull is computed only for a wanted feature that reads it, the diameter likewise.
  HullPart hull_part(std::string_view prefix) const {
    if (any_wanted_needing(FeatureFamily::kSurface, FeatureNeed::kConvexHull, prefix)) return HullPart::kCompute;
    if (any_wanted_needing(FeatureFamily::kSurface, FeatureNeed::kDiameter3d, prefix)) return HullPart::kDiameterOnly;
    return HullPart::kSkip;
  }
};

// The wanted features of `family`, read from `sources`, in catalogue order. `inside_on_own_grid`:
// the region is the inside one and the image shares the structure's grid; the features that need
// that are left out elsewhere (their sources were not computed).
void add_family(FeatureReport& report, FeatureFamily family, const FeatureSources& sources, const Ask& ask,
                std::string_view prefix = "", const std::string& region = "", const std::string& image = "",
                bool inside_on_own_grid = true) {
  for (const FeatureDef& f : feature_catalogue()) {
    if (f.family != family) continue;
    if (!inside_on_own_grid && f.needs.has(FeatureNeed::kImageOnGrid)) continue;
    if (region != "" && region != "inside" && f.needs.has(FeatureNeed::kInsideRegion)) continue;
    if (f.needs.has(FeatureNeed::kCoverage) && (!ask.coverage || (region == "inside" && !sources.weighted))) continue;
    const std::string name = std::string(prefix) + std::string(f.name);
    if (ask.wanted(name)) report.features.push_back({name, f.value(sources), region, image});
  }
}

Status volume_section(const Ask& ask, FeatureReport& report) {
  PartTimer timer(report);
  SOIQ_ASSIGN_OR_RETURN(
      VolumeShape v, timer.run("volume shape", [&] { return volume_shape(ask.input.volume, ask.request.covariance); }));
  FeatureSources sources;
  sources.volume = &v;
  double covered_mm3 = 0;
  if (ask.coverage) {
    covered_mm3 = covered_voxels(*ask.coverage) * ask.input.volume.geometry.voxel_volume_mm3();
    sources.covered_volume_mm3 = &covered_mm3;
  }
  add_family(report, FeatureFamily::kVolume, sources, ask);
  return ok_status();
}

Status stored_surface_section(const Ask& ask, FeatureReport& report) {
  PartTimer timer(report);
  SOIQ_ASSIGN_OR_RETURN(SurfaceShape s, timer.run("surface shape", [&] {
    return surface_shape(*ask.input.surface, ask.input.volume.geometry.frame(), ask.hull_part(""));
  }));
  FeatureSources sources;
  sources.surface = &s;
  add_family(report, FeatureFamily::kSurface, sources, ask);
  return ok_status();
}

// On an unevenly spaced grid the sweep's closed forms (one cube size) do not hold: the same
// marching-cubes surface is built in mm (mask_surface_mesh.h) and measured as a stored one is.
Status uneven_mask_surface_section(const Ask& ask, const std::optional<std::string>& prefix, FeatureReport& report) {
  PartTimer timer(report);
  const ImageGeometry& grid = ask.input.volume.geometry;
  SOIQ_ASSIGN_OR_RETURN(const TriangleMesh mesh, timer.run("mask surface mesh", [&] {
    return mask_surface_mesh(ask.input.volume, marching_cubes_table(), grid.voxel_count());
  }));
  if (prefix) {
    SOIQ_ASSIGN_OR_RETURN(SurfaceShape s, timer.run("mask surface shape", [&] {
      return surface_shape(mesh, grid.frame(), ask.hull_part(*prefix));
    }));
    FeatureSources sources;
    sources.surface = &s;
    add_family(report, FeatureFamily::kSurface, sources, ask, *prefix);
  }
  if (ask.any_wanted(FeatureFamily::kDiameter2d)) {
    SOIQ_ASSIGN_OR_RETURN(Maximum2DDiameters d,
                          timer.run("2d diameters", [&] { return maximum_2d_diameters(mesh, grid); }));
    FeatureSources sources;
    sources.diameters_2d = &d;
    add_family(report, FeatureFamily::kDiameter2d, sources, ask);
  }
  return ok_status();
}

// The mask's marching-cubes surface is never built: its features come from one sweep of the runs
// (mask_surface_sweep.h), exactly those of marching_cubes(mask) up to rounding. `prefix` is "" when
// they are the structure's surface features, "mask_" beside a stored surface's; empty optional:
// only the 2D diameters are asked.
Status mask_surface_section(const Ask& ask, const std::optional<std::string>& prefix, FeatureReport& report) {
  PartTimer timer(report);
  const ImageGeometry& grid = ask.input.volume.geometry;
  if (grid.uneven()) return uneven_mask_surface_section(ask, prefix, report);
  SOIQ_ASSIGN_OR_RETURN(const MaskSurfaceSweep sweep,
                        timer.run("mask surface sweep", [&] { return mask_surface_sweep(ask.input.volume); }));
  if (prefix) {
    SOIQ_ASSIGN_OR_RETURN(SurfaceShape s, timer.run("mask surface shape", [&] {
      return mask_surface_shape(sweep, grid, marching_cubes_table(), ask.hull_part(*prefix));
    }));
    FeatureSources sources;
    sources.surface = &s;
    add_family(report, FeatureFamily::kSurface, sources, ask, *prefix);
  }
  if (ask.any_wanted(FeatureFamily::kDiameter2d)) {
    SOIQ_ASSIGN_OR_RETURN(Maximum2DDiameters d,
                          timer.run("2d diameters", [&] { return mask_maximum_2d_diameters(sweep, grid); }));
    FeatureSources sources;
    sources.diameters_2d = &d;
    add_family(report, FeatureFamily::kDiameter2d, sources, ask);
  }
  return ok_status();
}

// One region and the intensity features of every image in it.
Status region_section(const Ask& ask, const RegionSpec& spec, FeatureReport& report) {
  PartTimer timer(report);
  const FeatureRequest& request = ask.request;
  const std::string rname = region_name(spec);
  RegionOptions options;
  options.threads = request.threads;
  SOIQ_ASSIGN_OR_RETURN(RunLengthVolume r,
                        timer.run("region " + rname, [&] { return region(ask.input.volume, spec, options); }));
  if (voxel_count(r) == 0) {
    return invalid_argument("region " + rname + " of the structure is empty (" + describe(r.geometry) +
                            "); choose a smaller radius or a finer grid");
  }
  for (const NamedImage& img : request.images) {
    if (img.image == nullptr) return invalid_argument("image '" + img.name + "' was not given");
    SOIQ_ASSIGN_OR_RETURN(RegionSamples samples, timer.run("resample " + img.name + " " + rname, [&] {
      return resample(*img.image, r, request.interpolation);
    }));
    if (samples.values.empty() && samples.non_finite > 0) {
      return invalid_argument("image '" + img.name + "' is NaN or infinite at every voxel of region " + rname + " (" +
                              std::to_string(samples.non_finite) + " voxels)");
    }
    if (samples.values.empty()) {
      return invalid_argument("no voxel of region " + rname + " lies inside image '" + img.name +
                              "': is it in the structure's frame of reference?");
    }
    SOIQ_ASSIGN_OR_RETURN(IntensityFeatures f, timer.run("intensity " + img.name + " " + rname, [&] {
      return intensity_features(std::move(samples.values));
    }));
    FeatureSources sources;
    sources.intensity = &f;
    std::optional<WeightedIntensity> weighted;
    if (spec.kind == RegionKind::kInside && ask.coverage &&
        ask.any_wanted_needing(FeatureFamily::kIntensity, FeatureNeed::kCoverage)) {
      SOIQ_ASSIGN_OR_RETURN(weighted, timer.run("weighted intensity " + img.name, [&]() -> Result<WeightedIntensity> {
        SOIQ_ASSIGN_OR_RETURN(const WeightedSamples w,
                              resample_weighted(*img.image, *ask.coverage, request.interpolation));
        return weighted_intensity(w.values, w.weights, ask.input.volume.geometry.voxel_volume_mm3());
      }));
      sources.weighted = &*weighted;
    }
    const bool inside_on_own_grid =
        spec.kind == RegionKind::kInside && check_same_grid(img.image->geometry, ask.input.volume.geometry).ok();
    double shift = 0;
    if (inside_on_own_grid && ask.any_wanted_needing(FeatureFamily::kIntensity, FeatureNeed::kImageOnGrid)) {
      SOIQ_ASSIGN_OR_RETURN(shift, timer.run("centre of mass shift " + img.name,
                                             [&] { return centre_of_mass_shift_mm(ask.input.volume, *img.image); }));
      sources.centre_of_mass_shift_mm = &shift;
    }
    add_family(report, FeatureFamily::kIntensity, sources, ask, "", rname, img.name, inside_on_own_grid);
  }
  return ok_status();
}

}  // namespace

Result<FeatureReport> structure_features(const StructureInput& input, const FeatureRequest& request) {
  const bool has_surface = input.surface != nullptr;
  for (const std::string& n : request.names) {
    SOIQ_RETURN_IF_ERROR(check_feature_name(n));
    if (!has_surface && mask_feature(n)) {
      return invalid_argument(
          "'" + n + "' is the mask surface's value beside a stored surface, and this structure has none: ask for '" +
          n.substr(kMaskPrefix.size()) + "'");
    }
  }

  // voxel_count is both a shape and an intensity name: only the intensity-only names need an image.
  const bool intensity_asked = std::any_of(request.names.begin(), request.names.end(),
                                           [](const std::string& n) { return is_intensity_only(n); });
  if (intensity_asked && request.images.empty()) {
    return invalid_argument("intensity features need an image in the structure's frame of reference (--image)");
  }
  if (voxel_count(input.volume) == 0) return invalid_argument("the structure has no voxels inside its grid");
  // The report tells images and regions apart by name: a name twice would give two values under one key.
  for (size_t i = 0; i < request.images.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (request.images[i].name == request.images[j].name) {
        return invalid_argument("image name '" + request.images[i].name +
                                "' is given twice; give each image its own name (--image NAME=PATH)");
      }
    }
  }
  for (size_t i = 0; i < request.regions.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (region_name(request.regions[i]) == region_name(request.regions[j])) {
        return invalid_argument("region " + region_name(request.regions[i]) + " is asked twice");
      }
    }
  }

  // The work in independent sections, each filling its own report, listed in report order. With
  // threads > 1 they run at once on core's pool (run_tasks.h); the report never depends on the
  // thread count. A section stops at its first error, and the first failing section's error is
  // returned, as a sequential run would.
  // Coverage fractions of the stored surface, once, for every weighted feature asked.
  std::optional<CoverageVolume> coverage;
  FeatureReport coverage_part;
  const bool weighted_asked =
      std::any_of(request.names.begin(), request.names.end(), [](const std::string& n) { return Ask::is_weighted(n); });
  if (weighted_asked) {
    if (!has_surface) {
      return invalid_argument(
          "coverage-weighted features (" + std::string(weighted_feature_names().front()) +
          ", ...) are weighted by the fractions of the structure's surface model, and this structure is a mask: ask "
          "for the unweighted ones (mean, variance, ...)");
    }
    PartTimer timer(coverage_part);
    CoverageOptions options;
    options.lines_per_voxel = kWeightedFeatureLines;
    options.fill_rule = request.fill_rule;
    options.threads = request.threads;
    options.max_voxels = input.volume.geometry.voxel_count();
    options.name = "the structure's surface";
    SOIQ_ASSIGN_OR_RETURN(coverage, timer.run("coverage fractions", [&] {
      return coverage_1d(*input.surface, input.volume.geometry, options);
    }));
  }
  const Ask ask{input, request, coverage ? &*coverage : nullptr};
  std::vector<std::function<Status(FeatureReport&)>> sections;
  std::vector<int> cost_rank;  // higher starts earlier, so the longest sections do not start last
  auto add = [&](int rank, std::function<Status(FeatureReport&)> section) {
    cost_rank.push_back(rank);
    sections.push_back(std::move(section));
  };
  if (ask.any_wanted(FeatureFamily::kVolume)) add(0, [&](FeatureReport& r) { return volume_section(ask, r); });
  if (has_surface && ask.any_wanted(FeatureFamily::kSurface)) {
    add(1, [&](FeatureReport& r) { return stored_surface_section(ask, r); });
  }
  std::optional<std::string> mask_prefix;
  if (!has_surface && ask.any_wanted(FeatureFamily::kSurface)) mask_prefix = "";
  if (has_surface && ask.any_wanted(FeatureFamily::kSurface, kMaskPrefix)) mask_prefix = std::string(kMaskPrefix);
  if (mask_prefix || ask.any_wanted(FeatureFamily::kDiameter2d)) {
    add(1, [&](FeatureReport& r) { return mask_surface_section(ask, mask_prefix, r); });
  }
  if (!request.images.empty() && ask.any_wanted(FeatureFamily::kIntensity)) {
    for (const RegionSpec& spec : request.regions) {
      add(2, [&ask, &spec](FeatureReport& r) { return region_section(ask, spec, r); });
    }
  }

  std::vector<size_t> order(sections.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost_rank[a] > cost_rank[b]; });
  std::vector<FeatureReport> parts(sections.size());
  std::vector<Status> status(sections.size(), ok_status());
  run_tasks(int64_t(sections.size()), request.threads, [&](int64_t t) {
    const size_t i = order[size_t(t)];
    status[i] = sections[i](parts[i]);
  });
  FeatureReport report;
  report.timings_ms = coverage_part.timings_ms;
  for (size_t i = 0; i < sections.size(); ++i) {
    SOIQ_RETURN_IF_ERROR(status[i]);
    report.features.insert(report.features.end(), parts[i].features.begin(), parts[i].features.end());
    report.timings_ms.insert(report.timings_ms.end(), parts[i].timings_ms.begin(), parts[i].timings_ms.end());
  }
  return report;
}

}  // namespace soiq
