#pragma once
// The one entry point for the features of a structure (docs/DESIGN.md "Features"): computes a
// requested set, says what it computed, and how long each part took, so the service can cache
// parts and explain a slow query.
//
// Inputs
//   input.volume   the structure's voxels on its grid (a mask, or the 1D method's result for a
//                  surface model). Required, non-empty.
//   input.surface  the stored surface model (LPS mm, closed), when the structure has one.
//   request.names  feature names (below); empty = every feature the inputs allow, except the
//                  coverage-weighted ones ("_w"), computed only when named.
//   request.regions / images / interpolation: where and on which images intensity features are
//                  taken (regions.h, resample.h); images must share the structure's frame of
//                  reference (any grid).
// Output (names are part of the API, listed with units and definitions in feature_catalogue.h):
//   volume:  voxel_count, voxel_volume_mm3, centroid_mm[3], bbox_mm[6] (min xyz, max xyz),
//            major/minor/least_axis_length_mm, elongation, flatness (volume_shape.h)
//   surface: mesh_volume_mm3, surface_area_mm2, surface_volume_ratio, sphericity, compactness_1,
//            compactness_2, spherical_disproportion, asphericity, maximum_3d_diameter_mm,
//            volume_density_aabb, area_density_aabb, volume_density_convex_hull,
//            area_density_convex_hull (surface_shape.h) — of the stored surface model when there
//            is one, else of the mask's marching-cubes surface (as IBSI and PyRadiomics do). With a
//            stored surface, the mask-surface values are also given, prefixed "mask_".
//   maximum_2d_diameter_slice_mm / _column_mm / _row_mm: always of the mask's marching-cubes
//            surface, whose vertices lie on the grid's (half-)voxel planes (maximum_2d_diameters.h;
//            computed from the runs: mask_maximum_2d_diameters.h, mask_surface_shape.h).
//   per region and image: mean, standard_deviation, variance, skewness, excess_kurtosis, minimum,
//            maximum, median, p10, p90, interquartile_range, range, mean_absolute_deviation,
//            energy, root_mean_square, voxel_count (intensity_features.h); for the inside region
//            also centre_of_mass_shift_mm (when the image shares the structure's grid).
//   coverage-weighted, named only, with a stored surface: volume_w_mm3; for the inside region and
//            each image voxel_count_w, mean_w, variance_w, standard_deviation_w,
//            root_mean_square_w, integrated_intensity_w (weighted_intensity.h), weighted by the
//            surface's coverage fractions on the grid (coverage_1d.h, 4 x 4 lines per voxel).
// Errors
//   INVALID_ARGUMENT  an unknown feature name (the message lists the known ones), intensity
//                     features asked without an image, an empty structure, an image in another
//                     frame of reference (no region voxel inside it), an empty region.
//   Others as the parts report them.
// Cost: the sum of the parts requested. The mask's marching-cubes surface is never built: its
// features come from one O(runs) sweep shared by the mask surface shape and the 2D diameters.
// Threads: request.threads > 1 runs the independent sections at once on core's pool (run_tasks.h):
// volume shape; the stored surface; the mask sweep with its surface and 2D diameters; each region
// with its images. The report is the same for any thread count (features, order, values bit for
// bit, parts); each part's time is then its own wall time, so they can add up to more than the
// call. On our 2-vCPU machines two threads take SM1's full set from 11 to 7 ms (BENCHMARKS.md).
// Safe to call from several threads at once.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/fill_rule.h"
#include "core/base/image.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/features/feature_catalogue.h"
#include "core/features/volume_shape.h"
#include "core/regions/regions.h"
#include "core/regions/resample.h"

namespace soiq {

struct StructureInput {
  RunLengthVolume volume;
  // Shared, not copied: a service keeps decoded surfaces in a cache, and a copy of a large one
  // cost a tenth of its conversion.
  std::shared_ptr<const TriangleMesh> surface;
};

struct NamedImage {
  std::string name;  // e.g. "PET", "CT"
  const Image* image = nullptr;
};

struct FeatureRequest {
  std::vector<std::string> names;
  std::vector<RegionSpec> regions = {RegionSpec{}};  // inside
  std::vector<NamedImage> images;
  Interpolation interpolation = Interpolation::kNearest;
  CovarianceDivisor covariance = CovarianceDivisor::kN;  // PyRadiomics; kNMinus1 for IBSI
  FillRule fill_rule = FillRule::kNonZero;               // of the surface, for the coverage-weighted features
  int threads = 1;  // >= 1: sections at once (Threads, above), and the regions' distance transform
};

struct Feature {
  std::string name;
  std::vector<double> value;  // one number, or an array (centroid_mm, bbox_mm)
  std::string region;         // "" for shape features; region_name(): "inside", "shell:5", "core:2"
  std::string image;          // "" for shape features
};

struct FeatureReport {
  std::vector<Feature> features;
  std::vector<std::pair<std::string, double>> timings_ms;  // part -> milliseconds
};

Result<FeatureReport> structure_features(const StructureInput& input, const FeatureRequest& request);

}  // namespace soiq
