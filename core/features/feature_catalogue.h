#pragma once
// Every feature soiq computes, in one table (DESIGN.md "Features"): its name, which is part of
// the API, its family, unit, what it needs, the version of its definition, a one-line summary and
// where its value is read from. structure_features computes from it, the query parser and the
// service validate names against it, the CLI and `soiq info` list it: a name is known in one place.
//
// Families and names:
//   volume      of the voxels (volume_shape.h): voxel_count, voxel_volume_mm3, centroid_mm[3],
//               bbox_mm[6] (min xyz, max xyz), the axis lengths, elongation, flatness.
//   surface     of the stored surface model when there is one, else of the mask's marching-cubes
//               surface (surface_shape.h, mask_surface_shape.h). Beside a stored surface the mask
//               surface's value of each is also available as "mask_" + name (mask_feature()).
//   diameter_2d of the mask's marching-cubes surface in the grid's slice, column and row planes.
//   intensity   per region and image (intensity_features.h), and centre_of_mass_shift_mm for the
//               inside region of an image on the structure's own grid.
// voxel_count is the one name in two families: the structure's voxels (volume) and a region's
// samples on an image (intensity); lookups are per family for that reason.
//
// Thread-safe (constant data). O(1) per lookup but known_feature_names (O(catalogue)).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"
#include "core/features/intensity_features.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/features/surface_shape.h"
#include "core/features/volume_shape.h"

namespace soiq {

enum class FeatureFamily { kVolume, kSurface, kDiameter2d, kIntensity };

// The records a feature's value is read from; a feature reads only its family's.
struct FeatureSources {
  const VolumeShape* volume = nullptr;
  const SurfaceShape* surface = nullptr;  // the stored surface's, or the mask surface's
  const Maximum2DDiameters* diameters_2d = nullptr;
  const IntensityFeatures* intensity = nullptr;
  const double* centre_of_mass_shift_mm = nullptr;
};

struct FeatureDef {
  std::string_view name;
  FeatureFamily family;
  std::string_view unit;  // "mm3", "mm", "1/mm", "voxels", "image" (the image's own unit), "" (none)
  std::string_view summary;
  int components = 1;       // 3: centroid_mm, 6: bbox_mm
  bool needs_hull = false;  // read from the convex hull or its diameter (computed only when asked)
  // Bumped when the definition changes, so that values cached under an older one are recomputed.
  int version = 1;
  std::vector<double> (*value)(const FeatureSources&) = nullptr;
};

// "volume", "surface", "diameter_2d", "intensity".
std::string_view family_name(FeatureFamily family);
// What computing the feature needs, in words: "voxels", "surface", "surface, convex hull",
// "image, region", "image on the structure's grid, inside region".
std::string_view feature_needs(const FeatureDef& feature);

// Every feature, in report order: volume, surface, 2D diameters, intensity.
std::span<const FeatureDef> feature_catalogue();

// The feature of `family` named `name`, or nullptr.
const FeatureDef* find_feature(FeatureFamily family, std::string_view name);
// A structure-level (volume, surface or 2D-diameter) feature named `name`, or nullptr.
const FeatureDef* find_shape_feature(std::string_view name);
// The intensity feature named `name`, or nullptr.
const FeatureDef* find_intensity_feature(std::string_view name);

// The prefix of the mask surface's values beside a stored surface's.
inline constexpr std::string_view kMaskPrefix = "mask_";
// For "mask_" + a surface feature's name, that surface feature; nullptr for any other name.
const FeatureDef* mask_feature(std::string_view name);

// The sum of every definition's version: part of the feature cache's key, so that bumping any
// definition invalidates cached values.
int feature_definitions_version();

// "voxel_count, voxel_volume_mm3, ..." for messages that list what is known: the shape names,
// then the intensity-only ones, then "mask_<surface feature>".
std::string known_feature_names();

// OK when `name` is a shape, intensity or mask_ surface feature; else INVALID_ARGUMENT "unknown
// feature 'name'; known features: ..." (known_feature_names).
Status check_feature_name(std::string_view name);

// True when `name` is only an intensity feature: it needs an image (voxel_count does not).
bool is_intensity_only(std::string_view name);

// The names of the shape (volume, surface, 2D diameter) features and of the intensity features,
// in catalogue order.
const std::vector<std::string>& shape_feature_names();
const std::vector<std::string>& intensity_feature_names();

}  // namespace soiq
