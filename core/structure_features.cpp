#include "core/structure_features.h"

#include <algorithm>
#include <chrono>
#include <functional>

#include "core/centre_of_mass_shift.h"
#include "core/intensity_features.h"
#include "core/io/marching_cubes_cases.h"
#include "core/mask_maximum_2d_diameters.h"
#include "core/mask_surface_shape.h"
#include "core/mask_surface_sweep.h"
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

void add_surface(FeatureReport& report, const SurfaceShape& s, const std::string& prefix,
                 const std::function<bool(const std::string&)>& wanted) {
  const double values[] = {
      s.mesh_volume_mm3,         s.surface_area_mm2,    s.surface_volume_ratio,    s.sphericity,
      s.compactness_1,           s.compactness_2,       s.spherical_disproportion, s.asphericity,
      s.maximum_3d_diameter_mm,  s.volume_density_aabb, s.area_density_aabb,       s.volume_density_convex_hull,
      s.area_density_convex_hull};
  for (size_t i = 0; i < kSurfaceNames.size(); ++i) {
    if (wanted(prefix + kSurfaceNames[i])) report.features.push_back({prefix + kSurfaceNames[i], {values[i]}, "", ""});
  }
}

void add_intensity(FeatureReport& report, const IntensityFeatures& f, const std::string& region,
                   const std::string& image, const std::function<bool(const std::string&)>& wanted) {
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
    if (wanted(kIntensityNames[i])) report.features.push_back({kIntensityNames[i], {values[i]}, region, image});
  }
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
  auto wanted = [&](const std::string& n) { return request.names.empty() || contains(request.names, n); };
  auto any_wanted = [&](const std::vector<std::string>& list, const std::string& prefix = "") {
    return std::any_of(list.begin(), list.end(), [&](const std::string& n) { return wanted(prefix + n); });
  };
  // voxel_count is both a shape and an intensity name: only the intensity-only names need an image.
  const bool intensity_asked = std::any_of(request.names.begin(), request.names.end(), [](const std::string& n) {
    return contains(kIntensityNames, n) && !contains(shape_feature_names(), n);
  });
  if (intensity_asked && request.images.empty()) {
    return invalid_argument("intensity features need an image in the structure's frame of reference (--image)");
  }
  if (voxel_count(input.volume) == 0) return invalid_argument("the structure has no voxels inside its grid");

  FeatureReport report;
  PartTimer timer(report);
  if (any_wanted(kVolumeNames)) {
    SOIQ_ASSIGN_OR_RETURN(VolumeShape v,
                          timer.run("volume shape", [&] { return volume_shape(input.volume, request.covariance); }));
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
      if (wanted(name)) report.features.push_back({name, value, "", ""});
    }
  }

  const bool need_mask_surface = any_wanted(kDiameter2dNames) || (!has_surface && any_wanted(kSurfaceNames)) ||
                                 (has_surface && any_wanted(kSurfaceNames, "mask_"));
  // The mask's marching-cubes surface is never built: its features come from one sweep of the
  // runs (mask_surface_sweep.h), exactly those of marching_cubes(mask) up to rounding.
  std::optional<MaskSurfaceSweep> sweep;
  if (need_mask_surface) {
    SOIQ_ASSIGN_OR_RETURN(MaskSurfaceSweep swept,
                          timer.run("mask surface sweep", [&] { return mask_surface_sweep(input.volume); }));
    sweep = std::move(swept);
  }
  const ImageGeometry& grid = input.volume.geometry;
  auto mask_shape = [&] { return mask_surface_shape(*sweep, grid, marching_cubes_cases()); };
  if (any_wanted(kSurfaceNames)) {
    SOIQ_ASSIGN_OR_RETURN(
        SurfaceShape s, has_surface
                            ? timer.run("surface shape", [&] { return surface_shape(*input.surface, grid.direction); })
                            : timer.run("mask surface shape", mask_shape));
    add_surface(report, s, "", wanted);
  }
  if (has_surface && any_wanted(kSurfaceNames, "mask_")) {
    SOIQ_ASSIGN_OR_RETURN(SurfaceShape s, timer.run("mask surface shape", mask_shape));
    add_surface(report, s, "mask_", wanted);
  }
  if (any_wanted(kDiameter2dNames)) {
    SOIQ_ASSIGN_OR_RETURN(Maximum2DDiameters d, timer.run("2d diameters", [&] {
      return mask_maximum_2d_diameters(*sweep, grid.spacing_mm);
    }));
    const double values[] = {d.slice_mm, d.column_mm, d.row_mm};
    for (size_t i = 0; i < 3; ++i) {
      if (wanted(kDiameter2dNames[i])) report.features.push_back({kDiameter2dNames[i], {values[i]}, "", ""});
    }
  }

  if (request.images.empty() || !any_wanted(kIntensityNames)) return report;
  RegionOptions region_options;
  region_options.threads = request.threads;
  for (const RegionSpec& spec : request.regions) {
    const std::string rname = region_name(spec);
    SOIQ_ASSIGN_OR_RETURN(RunLengthVolume r,
                          timer.run("region " + rname, [&] { return region(input.volume, spec, region_options); }));
    if (voxel_count(r) == 0) {
      return invalid_argument("region " + rname + " of the structure is empty (" + describe(r.geometry) +
                              "); choose a smaller radius or a finer grid");
    }
    for (const NamedImage& img : request.images) {
      if (img.image == nullptr) return invalid_argument("image '" + img.name + "' was not given");
      SOIQ_ASSIGN_OR_RETURN(RegionSamples samples, timer.run("resample " + img.name + " " + rname, [&] {
        return resample(*img.image, r, request.interpolation);
      }));
      if (samples.values.empty()) {
        return invalid_argument("no voxel of region " + rname + " lies inside image '" + img.name +
                                "': is it in the structure's frame of reference?");
      }
      SOIQ_ASSIGN_OR_RETURN(IntensityFeatures f, timer.run("intensity " + img.name + " " + rname, [&] {
        return intensity_features(std::move(samples.values));
      }));
      add_intensity(report, f, rname, img.name, wanted);
      if (spec.kind == RegionKind::kInside && wanted("centre_of_mass_shift_mm") &&
          check_same_grid(img.image->geometry, input.volume.geometry).ok()) {
        SOIQ_ASSIGN_OR_RETURN(double shift, timer.run("centre of mass shift " + img.name, [&] {
          return centre_of_mass_shift_mm(input.volume, *img.image);
        }));
        report.features.push_back({"centre_of_mass_shift_mm", {shift}, rname, img.name});
      }
    }
  }
  return report;
}

}  // namespace soiq
