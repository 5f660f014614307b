#include "core/structure_features.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>

#include "core/centre_of_mass_shift.h"
#include "core/intensity_features.h"
#include "core/io/marching_cubes_cases.h"
#include "core/mask_maximum_2d_diameters.h"
#include "core/mask_surface_shape.h"
#include "core/mask_surface_sweep.h"
#include "core/run_tasks.h"
#include "core/surface_shape.h"

namespace soiq {

namespace {

const std::vector<std::string> kVolumeNames = {
    "voxel_count",          "voxel_volume_mm3",     "centroid_mm", "bbox_mm", "major_axis_length_mm",
    "minor_axis_length_mm", "least_axis_length_mm", "elongation",  "flatness"};
const std::vector<std::string> kSurfaceNames = {
    "mesh_volume_mm3",         "surface_area_mm2",    "surface_volume_ratio",    "sphericity",
    "compactness_1",           "compactness_2",       "spherical_disproportion", "asphericity",
    "maximum_3d_diameter_mm",  "volume_density_aabb", "area_density_aabb",       "volume_density_convex_hull",
    "area_density_convex_hull"};
const std::vector<std::string> kDiameter2dNames = {"maximum_2d_diameter_slice_mm", "maximum_2d_diameter_column_mm",
                                                   "maximum_2d_diameter_row_mm"};
const std::vector<std::string> kIntensityNames = {"mean",
                                                  "standard_deviation",
                                                  "variance",
                                                  "skewness",
                                                  "excess_kurtosis",
                                                  "minimum",
                                                  "maximum",
                                                  "median",
                                                  "p10",
                                                  "p90",
                                                  "interquartile_range",
                                                  "range",
                                                  "mean_absolute_deviation",
                                                  "energy",
                                                  "root_mean_square",
                                                  "voxel_count",
                                                  "centre_of_mass_shift_mm"};

bool contains(const std::vector<std::string>& list, const std::string& name) {
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
  bool wanted(const std::string& n) const { return request.names.empty() || contains(request.names, n); }
  bool any_wanted(const std::vector<std::string>& list, const std::string& prefix = "") const {
    return std::any_of(list.begin(), list.end(), [&](const std::string& n) { return wanted(prefix + n); });
  }
};

void add_surface(FeatureReport& report, const SurfaceShape& s, const std::string& prefix, const Ask& ask) {
  const double values[] = {
      s.mesh_volume_mm3,         s.surface_area_mm2,    s.surface_volume_ratio,    s.sphericity,
      s.compactness_1,           s.compactness_2,       s.spherical_disproportion, s.asphericity,
      s.maximum_3d_diameter_mm,  s.volume_density_aabb, s.area_density_aabb,       s.volume_density_convex_hull,
      s.area_density_convex_hull};
  for (size_t i = 0; i < kSurfaceNames.size(); ++i) {
    if (ask.wanted(prefix + kSurfaceNames[i]))
      report.features.push_back({prefix + kSurfaceNames[i], {values[i]}, "", ""});
  }
}

void add_intensity(FeatureReport& report, const IntensityFeatures& f, const std::string& region,
                   const std::string& image, const Ask& ask) {
  const double values[] = {f.mean,
                           f.standard_deviation,
                           f.variance,
                           f.skewness,
                           f.excess_kurtosis,
                           f.minimum,
                           f.maximum,
                           f.median,
                           f.p10,
                           f.p90,
                           f.interquartile_range,
                           f.range,
                           f.mean_absolute_deviation,
                           f.energy,
                           f.root_mean_square,
                           double(f.voxel_count)};
  for (size_t i = 0; i < std::size(values); ++i) {
    if (ask.wanted(kIntensityNames[i])) report.features.push_back({kIntensityNames[i], {values[i]}, region, image});
  }
}

Status volume_section(const Ask& ask, FeatureReport& report) {
  PartTimer timer(report);
  SOIQ_ASSIGN_OR_RETURN(
      VolumeShape v, timer.run("volume shape", [&] { return volume_shape(ask.input.volume, ask.request.covariance); }));
  const std::pair<const char*, std::vector<double>> values[] = {
      {"voxel_count", {double(v.voxel_count)}},
      {"voxel_volume_mm3", {v.voxel_volume_mm3}},
      {"centroid_mm", {v.centroid_mm[0], v.centroid_mm[1], v.centroid_mm[2]}},
      {"bbox_mm",
       {v.bbox_min_mm[0], v.bbox_min_mm[1], v.bbox_min_mm[2], v.bbox_max_mm[0], v.bbox_max_mm[1], v.bbox_max_mm[2]}},
      {"major_axis_length_mm", {v.major_axis_length_mm}},
      {"minor_axis_length_mm", {v.minor_axis_length_mm}},
      {"least_axis_length_mm", {v.least_axis_length_mm}},
      {"elongation", {v.elongation}},
      {"flatness", {v.flatness}}};
  for (const auto& [name, value] : values) {
    if (ask.wanted(name)) report.features.push_back({name, value, "", ""});
  }
  return ok_status();
}

Status stored_surface_section(const Ask& ask, FeatureReport& report) {
  PartTimer timer(report);
  SOIQ_ASSIGN_OR_RETURN(SurfaceShape s, timer.run("surface shape", [&] {
    return surface_shape(*ask.input.surface, ask.input.volume.geometry.direction);
  }));
  add_surface(report, s, "", ask);
  return ok_status();
}

// The mask's marching-cubes surface is never built: its features come from one sweep of the runs
// (mask_surface_sweep.h), exactly those of marching_cubes(mask) up to rounding. `prefix` is "" when
// they are the structure's surface features, "mask_" beside a stored surface's; empty optional:
// only the 2D diameters are asked.
Status mask_surface_section(const Ask& ask, const std::optional<std::string>& prefix, FeatureReport& report) {
  PartTimer timer(report);
  const ImageGeometry& grid = ask.input.volume.geometry;
  SOIQ_ASSIGN_OR_RETURN(const MaskSurfaceSweep sweep,
                        timer.run("mask surface sweep", [&] { return mask_surface_sweep(ask.input.volume); }));
  if (prefix) {
    SOIQ_ASSIGN_OR_RETURN(SurfaceShape s, timer.run("mask surface shape", [&] {
      return mask_surface_shape(sweep, grid, marching_cubes_cases());
    }));
    add_surface(report, s, *prefix, ask);
  }
  if (ask.any_wanted(kDiameter2dNames)) {
    SOIQ_ASSIGN_OR_RETURN(Maximum2DDiameters d,
                          timer.run("2d diameters", [&] { return mask_maximum_2d_diameters(sweep, grid.spacing_mm); }));
    const double values[] = {d.slice_mm, d.column_mm, d.row_mm};
    for (size_t i = 0; i < 3; ++i) {
      if (ask.wanted(kDiameter2dNames[i])) report.features.push_back({kDiameter2dNames[i], {values[i]}, "", ""});
    }
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
    add_intensity(report, f, rname, img.name, ask);
    if (spec.kind == RegionKind::kInside && ask.wanted("centre_of_mass_shift_mm") &&
        check_same_grid(img.image->geometry, ask.input.volume.geometry).ok()) {
      SOIQ_ASSIGN_OR_RETURN(double shift, timer.run("centre of mass shift " + img.name, [&] {
        return centre_of_mass_shift_mm(ask.input.volume, *img.image);
      }));
      report.features.push_back({"centre_of_mass_shift_mm", {shift}, rname, img.name});
    }
  }
  return ok_status();
}

}  // namespace

const std::vector<std::string>& shape_feature_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = kVolumeNames;
    all.insert(all.end(), kSurfaceNames.begin(), kSurfaceNames.end());
    all.insert(all.end(), kDiameter2dNames.begin(), kDiameter2dNames.end());
    return all;
  }();
  return names;
}

const std::vector<std::string>& intensity_feature_names() { return kIntensityNames; }

Result<FeatureReport> structure_features(const StructureInput& input, const FeatureRequest& request) {
  const bool has_surface = input.surface.has_value();
  for (const std::string& n : request.names) {
    const bool mask_variant = has_surface && n.rfind("mask_", 0) == 0 && contains(kSurfaceNames, n.substr(5));
    if (contains(shape_feature_names(), n) || contains(kIntensityNames, n) || mask_variant) continue;
    std::string known;
    for (const auto& k : shape_feature_names()) known += (known.empty() ? "" : ", ") + k;
    for (const auto& k : kIntensityNames) known += ", " + k;
    return invalid_argument("unknown feature '" + n + "'; known features: " + known +
                            (has_surface ? " (and mask_<surface feature>)" : ""));
  }

  // voxel_count is both a shape and an intensity name: only the intensity-only names need an image.
  const bool intensity_asked = std::any_of(request.names.begin(), request.names.end(), [](const std::string& n) {
    return contains(kIntensityNames, n) && !contains(shape_feature_names(), n);
  });
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
  const Ask ask{input, request};
  std::vector<std::function<Status(FeatureReport&)>> sections;
  std::vector<int> cost_rank;  // higher starts earlier, so the longest sections do not start last
  auto add = [&](int rank, std::function<Status(FeatureReport&)> section) {
    cost_rank.push_back(rank);
    sections.push_back(std::move(section));
  };
  if (ask.any_wanted(kVolumeNames)) add(0, [&](FeatureReport& r) { return volume_section(ask, r); });
  if (has_surface && ask.any_wanted(kSurfaceNames)) {
    add(1, [&](FeatureReport& r) { return stored_surface_section(ask, r); });
  }
  std::optional<std::string> mask_prefix;
  if (!has_surface && ask.any_wanted(kSurfaceNames)) mask_prefix = "";
  if (has_surface && ask.any_wanted(kSurfaceNames, "mask_")) mask_prefix = "mask_";
  if (mask_prefix || ask.any_wanted(kDiameter2dNames)) {
    add(1, [&](FeatureReport& r) { return mask_surface_section(ask, mask_prefix, r); });
  }
  if (!request.images.empty() && ask.any_wanted(kIntensityNames)) {
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
  for (size_t i = 0; i < sections.size(); ++i) {
    SOIQ_RETURN_IF_ERROR(status[i]);
    report.features.insert(report.features.end(), parts[i].features.begin(), parts[i].features.end());
    report.timings_ms.insert(report.timings_ms.end(), parts[i].timings_ms.begin(), parts[i].timings_ms.end());
  }
  return report;
}

}  // namespace soiq
