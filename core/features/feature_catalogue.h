#pragma once
// Every feature soiq computes, in one table (docs/DESIGN.md "Features"): its name, which is part of
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
//   "_w"        weighted by each voxel's coverage fraction (weighted_intensity.h): volume_w_mm3
//               (volume family) and, for the inside region, voxel_count_w, mean_w, variance_w,
//               standard_deviation_w, root_mean_square_w, integrated_intensity_w (intensity); they
//               need the stored surface, whose fractions on the grid they are weighted by.
// voxel_count is the one name in two families: the structure's voxels (volume) and a region's
// samples on an image (intensity); lookups are per family for that reason. Each entry's `needs`
// says what computing it takes (the convex hull, an image on the structure's own grid, ...), so
// that callers decide by them and never by a feature's name.
//
// Thread-safe (constant data). O(1) per lookup but known_feature_names (O(catalogue)).

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"
#include "core/features/intensity_features.h"
#include "core/features/maximum_2d_diameters.h"
#include "core/features/surface_shape.h"
#include "core/features/volume_shape.h"
#include "core/features/weighted_intensity.h"

namespace soiq {

enum class FeatureFamily { kVolume, kSurface, kDiameter2d, kIntensity };

// The records a feature's value is read from; a feature reads only its family's.
struct FeatureSources {
  const VolumeShape* volume = nullptr;
  const SurfaceShape* surface = nullptr;  // the stored surface's, or the mask surface's
  const Maximum2DDiameters* diameters_2d = nullptr;
  const IntensityFeatures* intensity = nullptr;
  const double* centre_of_mass_shift_mm = nullptr;
  const WeightedIntensity* weighted = nullptr;  // inside region, weighted by coverage fractions
  const double* covered_volume_mm3 = nullptr;   // sum of the coverage fractions x voxel volume
};

// The n of the n x n lines per voxel behind the coverage-weighted features ("_w"): fixed, so a
// value's definition does not depend on a request (coverage_1d.h: errors < 0.1 % of the volume at 4).
inline constexpr int kWeightedFeatureLines = 4;

// One thing computing a feature needs besides the structure (FeatureDef::needs).
enum class FeatureNeed : uint16_t {
  kVoxels = 1 << 0,        // the structure's voxels on its grid
  kSurface = 1 << 1,       // a surface: the stored one, else the mask's marching-cubes surface
  kConvexHull = 1 << 2,    // that surface's convex hull: its volume and area (computed only when asked)
  kImage = 1 << 3,         // an image in the structure's frame of reference
  kImageOnGrid = 1 << 4,   // that image on the structure's own grid (comes with kImage)
  kRegion = 1 << 5,        // a region of the structure: inside, shell or core
  kInsideRegion = 1 << 6,  // the inside region only (comes with kRegion)
  kDiameter3d = 1 << 7,    // that surface's largest vertex distance (computed only when asked)
  kCoverage = 1 << 8,      // the coverage fractions of the stored surface on the grid (coverage_1d.h)
};

// A set of FeatureNeed, written in the table as FeatureNeed::kSurface | FeatureNeed::kConvexHull.
class FeatureNeeds {
 public:
  constexpr FeatureNeeds(FeatureNeed need) : bits_(uint16_t(need)) {}  // implicit: a set of one
  constexpr FeatureNeeds operator|(FeatureNeeds other) const { return FeatureNeeds(uint16_t(bits_ | other.bits_)); }
  constexpr bool has(FeatureNeed need) const { return (bits_ & uint16_t(need)) != 0; }

 private:
  constexpr explicit FeatureNeeds(uint16_t bits) : bits_(bits) {}
  uint16_t bits_ = 0;
};

constexpr FeatureNeeds operator|(FeatureNeed a, FeatureNeed b) { return FeatureNeeds(a) | b; }

struct FeatureDef {
  std::string_view name;
  FeatureFamily family;
  std::string_view unit;  // "mm3", "mm", "1/mm", "voxels", "image" (the image's own unit), "" (none)
  std::string_view summary;
  int components = 1;  // values per structure (and region and image): 1, or an array (3 for a point)
  FeatureNeeds needs = FeatureNeed::kVoxels;
  // Bumped when the definition changes, so that values cached under an older one are recomputed.
  int version = 1;
  std::vector<double> (*value)(const FeatureSources&) = nullptr;
};

// "volume", "surface", "diameter_2d", "intensity".
std::string_view family_name(FeatureFamily family);
// What computing the feature needs, in words from its needs: "voxels", "surface", "surface, convex
// hull", "image, region", "image on the structure's grid, inside region".
std::string feature_needs(const FeatureDef& feature);

// Every feature, in report order: volume, surface, 2D diameters, intensity.
std::span<const FeatureDef> feature_catalogue();

// The feature that costs least beyond the structure's voxels (the voxel count): what to ask for
// when a caller needs a computation but no particular value.
const FeatureDef& cheapest_feature();

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

// "volume: voxel_count, ...; surface: ...; diameter_2d: ...; intensity: mean, ..." for messages
// that list what is known: real feature names only, grouped by family, then "mask_<surface feature>".
std::string known_feature_names();

// OK when `name` is a shape, intensity or mask_ surface feature; else INVALID_ARGUMENT "unknown
// feature 'name'; did you mean 'closest'? (known features by family: ...)" (known_feature_names;
// the did-you-mean only when a name is near, core/base/did_you_mean.h).
Status check_feature_name(std::string_view name);

// True when `name` is only an intensity feature: it needs an image (voxel_count does not).
bool is_intensity_only(std::string_view name);

// The names of the shape (volume, surface, 2D diameter) features and of the intensity features,
// in catalogue order: what "every feature" means, so without the coverage-weighted ones, which
// cost a conversion of their own and are computed only when named.
const std::vector<std::string>& shape_feature_names();
const std::vector<std::string>& intensity_feature_names();
// The coverage-weighted features (FeatureNeed::kCoverage), in catalogue order.
const std::vector<std::string>& weighted_feature_names();

}  // namespace soiq
