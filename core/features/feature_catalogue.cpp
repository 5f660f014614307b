#include "core/features/feature_catalogue.h"

#include <array>

#include "core/base/did_you_mean.h"

namespace soiq {
namespace {

using F = FeatureFamily;
using N = FeatureNeed;
using V = std::vector<double>;

constexpr FeatureNeeds kHull = N::kSurface | N::kConvexHull;
constexpr FeatureNeeds kImageRegion = N::kImage | N::kRegion;
constexpr FeatureNeeds kWeighted = N::kSurface | N::kCoverage | N::kImage | N::kRegion | N::kInsideRegion;
constexpr FeatureNeeds kOwnGridInside = N::kImage | N::kImageOnGrid | N::kRegion | N::kInsideRegion;

// The catalogue's own version: 2 since soiq's exact hull and one-pass area and volume. Each
// definition's bump adds to it (feature_definitions_version).
constexpr int kCatalogueVersion = 2;

const std::array kCatalogue = std::to_array<FeatureDef>({
    // Volume: of the voxels (volume_shape.h).
    {"voxel_count", F::kVolume, "voxels", "voxels inside the structure", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{double(s.volume->voxel_count)}; }},
    {"voxel_volume_mm3", F::kVolume, "mm3", "voxel count x voxel volume (IBSI YEKZ)", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{s.volume->voxel_volume_mm3}; }},
    {"volume_w_mm3", F::kVolume, "mm3", "sum of the voxels' coverage fractions x voxel volume (partial volume)", 1,
     N::kSurface | N::kCoverage, 1, [](const FeatureSources& s) { return V{*s.covered_volume_mm3}; }},
    {"centroid_mm", F::kVolume, "mm", "mean of the voxel centres, LPS x y z", 3, N::kVoxels, 1,
     [](const FeatureSources& s) {
       const Vec3& c = s.volume->centroid_mm;
       return V{c[0], c[1], c[2]};
     }},
    {"bbox_mm", F::kVolume, "mm", "voxel centres' bounding box: min x y z, max x y z", 6, N::kVoxels, 1,
     [](const FeatureSources& s) {
       const Vec3 &lo = s.volume->bbox_min_mm, &hi = s.volume->bbox_max_mm;
       return V{lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
     }},
    {"major_axis_length_mm", F::kVolume, "mm", "4 sqrt(largest eigenvalue) of the voxel covariance (IBSI TDIC)", 1,
     N::kVoxels, 1, [](const FeatureSources& s) { return V{s.volume->major_axis_length_mm}; }},
    {"minor_axis_length_mm", F::kVolume, "mm", "4 sqrt(second eigenvalue) (IBSI P9VJ)", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{s.volume->minor_axis_length_mm}; }},
    {"least_axis_length_mm", F::kVolume, "mm", "4 sqrt(smallest eigenvalue) (IBSI 7J51)", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{s.volume->least_axis_length_mm}; }},
    {"elongation", F::kVolume, "", "sqrt(minor / major eigenvalue) (IBSI Q3CK)", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{s.volume->elongation}; }},
    {"flatness", F::kVolume, "", "sqrt(least / major eigenvalue) (IBSI N17B)", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{s.volume->flatness}; }},

    // Surface: of the stored surface model, else of the mask's marching-cubes surface.
    {"mesh_volume_mm3", F::kSurface, "mm3", "volume V enclosed by the surface (IBSI RNU0)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->mesh_volume_mm3}; }},
    {"surface_area_mm2", F::kSurface, "mm2", "area A of the surface (IBSI C0JK)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->surface_area_mm2}; }},
    {"surface_volume_ratio", F::kSurface, "1/mm", "A / V (IBSI 2PR5)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->surface_volume_ratio}; }},
    {"sphericity", F::kSurface, "", "(36 pi V^2)^(1/3) / A (IBSI QCFX)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->sphericity}; }},
    {"compactness_1", F::kSurface, "", "V / (sqrt(pi) A^(3/2)) (IBSI SKGS)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->compactness_1}; }},
    {"compactness_2", F::kSurface, "", "36 pi V^2 / A^3 (IBSI BQWJ)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->compactness_2}; }},
    {"spherical_disproportion", F::kSurface, "", "A / (36 pi V^2)^(1/3) (IBSI KRCK)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->spherical_disproportion}; }},
    {"asphericity", F::kSurface, "", "(A^3 / (36 pi V^2))^(1/3) - 1 (IBSI 25C7)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->asphericity}; }},
    {"maximum_3d_diameter_mm", F::kSurface, "mm", "largest distance between two surface vertices (IBSI L0JK)", 1,
     N::kSurface | N::kDiameter3d, 1, [](const FeatureSources& s) { return V{s.surface->maximum_3d_diameter_mm}; }},
    {"volume_density_aabb", F::kSurface, "", "V / volume of the vertices' box along the grid axes (IBSI PBX1)", 1,
     N::kSurface, 1, [](const FeatureSources& s) { return V{s.surface->volume_density_aabb}; }},
    {"area_density_aabb", F::kSurface, "", "A / area of that box (IBSI R59B)", 1, N::kSurface, 1,
     [](const FeatureSources& s) { return V{s.surface->area_density_aabb}; }},
    {"volume_density_convex_hull", F::kSurface, "", "V / convex hull volume (IBSI R3ER)", 1, kHull, 1,
     [](const FeatureSources& s) { return V{s.surface->volume_density_convex_hull}; }},
    {"area_density_convex_hull", F::kSurface, "", "A / convex hull area (IBSI 7T7F)", 1, kHull, 1,
     [](const FeatureSources& s) { return V{s.surface->area_density_convex_hull}; }},

    // 2D diameters: of the mask's marching-cubes surface, in the grid's planes.
    {"maximum_2d_diameter_slice_mm", F::kDiameter2d, "mm", "largest diameter in a plane of constant k", 1, N::kVoxels,
     1, [](const FeatureSources& s) { return V{s.diameters_2d->slice_mm}; }},
    {"maximum_2d_diameter_column_mm", F::kDiameter2d, "mm", "largest diameter in a plane of constant j", 1, N::kVoxels,
     1, [](const FeatureSources& s) { return V{s.diameters_2d->column_mm}; }},
    {"maximum_2d_diameter_row_mm", F::kDiameter2d, "mm", "largest diameter in a plane of constant i", 1, N::kVoxels, 1,
     [](const FeatureSources& s) { return V{s.diameters_2d->row_mm}; }},

    // Intensity: per region and image (intensity_features.h).
    {"mean", F::kIntensity, "image", "mean (IBSI Q4LE)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->mean}; }},
    {"standard_deviation", F::kIntensity, "image", "square root of the variance", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->standard_deviation}; }},
    {"variance", F::kIntensity, "image", "variance, divisor N (IBSI ECT3)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->variance}; }},
    {"skewness", F::kIntensity, "", "skewness (IBSI KE2A)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->skewness}; }},
    {"excess_kurtosis", F::kIntensity, "", "kurtosis - 3 (IBSI IPH6)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->excess_kurtosis}; }},
    {"minimum", F::kIntensity, "image", "minimum (IBSI 1GSF)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->minimum}; }},
    {"maximum", F::kIntensity, "image", "maximum (IBSI 84IY)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->maximum}; }},
    {"median", F::kIntensity, "image", "median (IBSI Y12H)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->median}; }},
    {"p10", F::kIntensity, "image", "10th percentile (IBSI QG58)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->p10}; }},
    {"p90", F::kIntensity, "image", "90th percentile (IBSI 8DWT)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->p90}; }},
    {"interquartile_range", F::kIntensity, "image", "p75 - p25 (IBSI SALO)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->interquartile_range}; }},
    {"range", F::kIntensity, "image", "maximum - minimum (IBSI 2OJQ)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->range}; }},
    {"mean_absolute_deviation", F::kIntensity, "image", "mean |x - mean| (IBSI 4FUA)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->mean_absolute_deviation}; }},
    {"energy", F::kIntensity, "image^2", "sum of squares (IBSI N8CA)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->energy}; }},
    {"root_mean_square", F::kIntensity, "image", "sqrt(mean of squares) (IBSI 5ZWQ)", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{s.intensity->root_mean_square}; }},
    {"voxel_count", F::kIntensity, "voxels", "samples of the region inside the image", 1, kImageRegion, 1,
     [](const FeatureSources& s) { return V{double(s.intensity->voxel_count)}; }},
    {"centre_of_mass_shift_mm", F::kIntensity, "mm",
     "distance between the intensity-weighted and the plain centroid (IBSI KLMA); inside, same grid only", 1,
     kOwnGridInside, 1, [](const FeatureSources& s) { return V{*s.centre_of_mass_shift_mm}; }},

    // Weighted by coverage fractions (weighted_intensity.h; 4 x 4 lines per voxel): inside only.
    {"voxel_count_w", F::kIntensity, "voxels", "sum of the coverage fractions of the voxels inside the image", 1,
     kWeighted, 1, [](const FeatureSources& s) { return V{s.weighted->voxel_count}; }},
    {"mean_w", F::kIntensity, "image", "coverage-weighted mean: sum f x / sum f", 1, kWeighted, 1,
     [](const FeatureSources& s) { return V{s.weighted->mean}; }},
    {"variance_w", F::kIntensity, "image^2",
     "coverage-weighted population variance: sum f (x - mean_w)^2 / sum f (frequency weights)", 1, kWeighted, 1,
     [](const FeatureSources& s) { return V{s.weighted->variance}; }},
    {"standard_deviation_w", F::kIntensity, "image", "square root of variance_w", 1, kWeighted, 1,
     [](const FeatureSources& s) { return V{s.weighted->standard_deviation}; }},
    {"root_mean_square_w", F::kIntensity, "image", "sqrt(sum f x^2 / sum f)", 1, kWeighted, 1,
     [](const FeatureSources& s) { return V{s.weighted->root_mean_square}; }},
    {"integrated_intensity_w", F::kIntensity, "image mm3",
     "voxel volume x sum f x: IBSI 99N0 with partial volume (PET: total uptake)", 1, kWeighted, 1,
     [](const FeatureSources& s) { return V{s.weighted->integrated_intensity}; }},
});

}  // namespace

std::span<const FeatureDef> feature_catalogue() { return kCatalogue; }

// The table opens with it; tests/core/feature_catalogue_test.cpp checks that it needs voxels only.
const FeatureDef& cheapest_feature() { return kCatalogue.front(); }

std::string_view family_name(FeatureFamily family) {
  switch (family) {
    case FeatureFamily::kVolume:
      return "volume";
    case FeatureFamily::kSurface:
      return "surface";
    case FeatureFamily::kDiameter2d:
      return "diameter_2d";
    case FeatureFamily::kIntensity:
      return "intensity";
  }
  return "";
}

std::string feature_needs(const FeatureDef& f) {
  std::string words;
  auto add = [&](std::string_view w) { words += (words.empty() ? "" : ", ") + std::string(w); };
  if (f.needs.has(N::kVoxels)) add("voxels");
  if (f.needs.has(N::kSurface)) add("surface");
  if (f.needs.has(N::kConvexHull)) add("convex hull");
  if (f.needs.has(N::kDiameter3d)) add("3D diameter");
  if (f.needs.has(N::kCoverage)) add("coverage fractions");
  if (f.needs.has(N::kImageOnGrid)) {
    add("image on the structure's grid");
  } else if (f.needs.has(N::kImage)) {
    add("image");
  }
  if (f.needs.has(N::kInsideRegion)) {
    add("inside region");
  } else if (f.needs.has(N::kRegion)) {
    add("region");
  }
  return words;
}

const FeatureDef* find_feature(FeatureFamily family, std::string_view name) {
  for (const FeatureDef& f : kCatalogue)
    if (f.family == family && f.name == name) return &f;
  return nullptr;
}

const FeatureDef* find_shape_feature(std::string_view name) {
  for (const FeatureDef& f : kCatalogue)
    if (f.family != FeatureFamily::kIntensity && f.name == name) return &f;
  return nullptr;
}

const FeatureDef* find_intensity_feature(std::string_view name) {
  return find_feature(FeatureFamily::kIntensity, name);
}

const FeatureDef* mask_feature(std::string_view name) {
  if (!name.starts_with(kMaskPrefix)) return nullptr;
  return find_feature(FeatureFamily::kSurface, name.substr(kMaskPrefix.size()));
}

int feature_definitions_version() {
  int version = kCatalogueVersion;
  for (const FeatureDef& f : kCatalogue) version += f.version - 1;
  return version;
}

std::string known_feature_names() {
  // Grouped by family, so a reader scans the one they meant; voxel_count is listed once (volume).
  std::string known;
  for (const FeatureFamily family :
       {FeatureFamily::kVolume, FeatureFamily::kSurface, FeatureFamily::kDiameter2d, FeatureFamily::kIntensity}) {
    std::string names;
    for (const FeatureDef& f : kCatalogue) {
      if (f.family != family || (family == FeatureFamily::kIntensity && find_shape_feature(f.name))) continue;
      names += (names.empty() ? "" : ", ") + std::string(f.name);
    }
    known += (known.empty() ? "" : "; ") + std::string(family_name(family)) + ": " + names;
  }
  return known + " (and mask_<surface feature> beside a stored surface)";
}

Status check_feature_name(std::string_view name) {
  if (find_shape_feature(name) || find_intensity_feature(name) || mask_feature(name)) return ok_status();
  std::vector<std::string> names;
  for (const FeatureDef& f : kCatalogue) names.emplace_back(f.name);
  for (const FeatureDef& f : kCatalogue) {
    if (f.family == FeatureFamily::kSurface) names.push_back(std::string(kMaskPrefix) + std::string(f.name));
  }
  return invalid_argument("unknown feature '" + std::string(name) + "'" + did_you_mean(name, names) +
                          " (known features by family: " + known_feature_names() + ")");
}

bool is_intensity_only(std::string_view name) {
  return find_intensity_feature(name) != nullptr && find_shape_feature(name) == nullptr;
}

namespace {

std::vector<std::string> names_where(bool intensity) {
  std::vector<std::string> names;
  for (const FeatureDef& f : kCatalogue)
    if ((f.family == FeatureFamily::kIntensity) == intensity && !f.needs.has(N::kCoverage)) names.emplace_back(f.name);
  return names;
}

}  // namespace

const std::vector<std::string>& shape_feature_names() {
  static const std::vector<std::string> names = names_where(false);
  return names;
}

const std::vector<std::string>& intensity_feature_names() {
  static const std::vector<std::string> names = names_where(true);
  return names;
}

const std::vector<std::string>& weighted_feature_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const FeatureDef& f : kCatalogue)
      if (f.needs.has(N::kCoverage)) out.emplace_back(f.name);
    return out;
  }();
  return names;
}

}  // namespace soiq
