// The feature catalogue: one entry per name and family, each readable from its family's record
// with the number of values it declares; names checked in one place (mask_ only for surface
// features); and the convex hull computed only for the features that read it, the others
// unchanged bit for bit when it is skipped.
#include "core/features/feature_catalogue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "core/features/marching_cubes_table.h"
#include "core/features/mask_surface_shape.h"
#include "core/features/mask_surface_sweep.h"
#include "core/features/structure_features.h"
#include "core/geometry/primitives.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

TEST(FeatureCatalogue, NamesAreUniqueWithinAFamilyAndOnlyVoxelCountIsInTwo) {
  std::set<std::pair<int, std::string>> seen;
  std::map<std::string, int> families;
  for (const FeatureDef& f : feature_catalogue()) {
    EXPECT_TRUE(seen.insert({int(f.family), std::string(f.name)}).second) << f.name;
    ++families[std::string(f.name)];
  }
  for (const auto& [name, count] : families) EXPECT_EQ(count, name == "voxel_count" ? 2 : 1) << name;
}

TEST(FeatureCatalogue, EveryFeatureReadsItsRecordWithTheDeclaredNumberOfValues) {
  const VolumeShape volume;
  const SurfaceShape surface;
  const Maximum2DDiameters d2;
  const IntensityFeatures intensity;
  const double shift = 0.5;
  const WeightedIntensity weighted;
  const double covered = 3;
  const FeatureSources sources{&volume, &surface, &d2, &intensity, &shift, &weighted, &covered};
  for (const FeatureDef& f : feature_catalogue()) {
    ASSERT_NE(f.value, nullptr) << f.name;
    EXPECT_EQ(f.value(sources).size(), size_t(f.components)) << f.name;
    EXPECT_FALSE(f.summary.empty()) << f.name;
    EXPECT_GE(f.version, 1) << f.name;
    EXPECT_FALSE(feature_needs(f).empty()) << f.name;
    EXPECT_TRUE(f.family == FeatureFamily::kSurface || !f.needs.has(FeatureNeed::kConvexHull))
        << f.name << ": only surfaces have a hull";
  }
  EXPECT_GE(feature_definitions_version(), 2);
}

TEST(FeatureCatalogue, NeedsFollowTheFamilyAndRefinementsComeWithWhatTheyRefine) {
  for (const FeatureDef& f : feature_catalogue()) {
    const bool intensity = f.family == FeatureFamily::kIntensity;
    EXPECT_EQ(f.needs.has(FeatureNeed::kImage), intensity) << f.name;
    EXPECT_EQ(f.needs.has(FeatureNeed::kRegion), intensity) << f.name;
    // Coverage fractions come from the stored surface: the one refinement outside the surface family.
    EXPECT_EQ(f.needs.has(FeatureNeed::kSurface),
              f.family == FeatureFamily::kSurface || f.needs.has(FeatureNeed::kCoverage))
        << f.name;
    EXPECT_TRUE(!f.needs.has(FeatureNeed::kCoverage) || f.name.ends_with("_w") || f.name.ends_with("_w_mm3"))
        << f.name << ": weighted, named so";
    EXPECT_TRUE(!f.needs.has(FeatureNeed::kCoverage) || !intensity || f.needs.has(FeatureNeed::kInsideRegion))
        << f.name << ": only the inside region has coverage weights";
    EXPECT_TRUE(!f.needs.has(FeatureNeed::kImageOnGrid) || f.needs.has(FeatureNeed::kImage)) << f.name;
    EXPECT_TRUE(!f.needs.has(FeatureNeed::kInsideRegion) || f.needs.has(FeatureNeed::kRegion)) << f.name;
  }
}

TEST(FeatureCatalogue, NeedsReadAsWords) {
  EXPECT_EQ(feature_needs(*find_shape_feature("centroid_mm")), "voxels");
  EXPECT_EQ(feature_needs(*find_shape_feature("sphericity")), "surface");
  EXPECT_EQ(feature_needs(*find_shape_feature("maximum_3d_diameter_mm")), "surface, 3D diameter");
  EXPECT_EQ(feature_needs(*find_shape_feature("volume_density_convex_hull")), "surface, convex hull");
  EXPECT_EQ(feature_needs(*find_intensity_feature("mean")), "image, region");
  EXPECT_EQ(feature_needs(*find_intensity_feature("centre_of_mass_shift_mm")),
            "image on the structure's grid, inside region");
  EXPECT_EQ(feature_needs(*find_intensity_feature("mean_w")), "surface, coverage fractions, image, inside region");
  EXPECT_EQ(feature_needs(*find_shape_feature("volume_w_mm3")), "surface, coverage fractions");
}

TEST(FeatureCatalogue, TheCheapestFeatureNeedsOnlyTheVoxels) {
  const FeatureDef& f = cheapest_feature();
  EXPECT_EQ(f.family, FeatureFamily::kVolume);
  EXPECT_EQ(feature_needs(f), "voxels");
  EXPECT_EQ(f.components, 1);
}

TEST(FeatureCatalogue, NamesAreCheckedInOnePlace) {
  EXPECT_TRUE(check_feature_name("sphericity").ok());
  EXPECT_TRUE(check_feature_name("mean").ok());
  EXPECT_TRUE(check_feature_name("voxel_count").ok());
  EXPECT_TRUE(check_feature_name("mask_sphericity").ok());
  EXPECT_TRUE(check_feature_name("mask_maximum_3d_diameter_mm").ok());
  for (const char* bad : {"mask_voxel_count", "mask_mean", "mask_mask_sphericity", "sphericty", "", "where[0]"}) {
    const Status s = check_feature_name(bad);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(s.message().find("unknown feature '" + std::string(bad) + "'"), std::string::npos) << s.message();
    EXPECT_NE(s.message().find("sphericity"), std::string::npos) << s.message();
  }
  EXPECT_TRUE(is_intensity_only("mean"));
  EXPECT_FALSE(is_intensity_only("voxel_count"));
  EXPECT_FALSE(is_intensity_only("sphericity"));
  EXPECT_EQ(mask_feature("mask_sphericity"), find_feature(FeatureFamily::kSurface, "sphericity"));
  EXPECT_EQ(mask_feature("mask_voxel_count"), nullptr);
  EXPECT_EQ(known_feature_names().find("where"), std::string::npos);
}

TEST(FeatureCatalogue, AnUnknownNameGetsTheClosestFirstThenTheNamesByFamily) {
  const std::string m = check_feature_name("sphericty").message();
  EXPECT_NE(m.find("unknown feature 'sphericty'; did you mean 'sphericity'?"), std::string::npos) << m;
  const size_t volume = m.find("volume: voxel_count"), surface = m.find("; surface: "),
               intensity = m.find("; intensity: ");
  EXPECT_LT(m.find("did you mean"), volume) << m;
  EXPECT_LT(volume, surface) << m;
  EXPECT_LT(surface, intensity) << m;
  EXPECT_EQ(check_feature_name("mask_sphercity").message().find("did you mean 'mask_sphericity'?") == std::string::npos,
            false);
  EXPECT_EQ(check_feature_name("zzzzzzzz").message().find("did you mean"), std::string::npos);
}

// Bitwise equal doubles, NaN-aware.
void expect_same_hull_free(const SurfaceShape& a, const SurfaceShape& b) {
  EXPECT_EQ(a.mesh_volume_mm3, b.mesh_volume_mm3);
  EXPECT_EQ(a.surface_area_mm2, b.surface_area_mm2);
  EXPECT_EQ(a.surface_volume_ratio, b.surface_volume_ratio);
  EXPECT_EQ(a.sphericity, b.sphericity);
  EXPECT_EQ(a.compactness_1, b.compactness_1);
  EXPECT_EQ(a.compactness_2, b.compactness_2);
  EXPECT_EQ(a.spherical_disproportion, b.spherical_disproportion);
  EXPECT_EQ(a.asphericity, b.asphericity);
  EXPECT_EQ(a.volume_density_aabb, b.volume_density_aabb);
  EXPECT_EQ(a.area_density_aabb, b.area_density_aabb);
}

void expect_hull_skipped(const SurfaceShape& s, bool diameter_too = true) {
  EXPECT_EQ(std::isnan(s.maximum_3d_diameter_mm), diameter_too);
  EXPECT_TRUE(std::isnan(s.volume_density_convex_hull));
  EXPECT_TRUE(std::isnan(s.area_density_convex_hull));
  EXPECT_TRUE(std::isnan(s.convex_hull_volume_mm3));
}

TEST(FeatureCatalogue, SkippingTheHullChangesNoOtherValue) {
  const TriangleMesh mesh = uv_sphere({1.5, -2, 3}, 9.7, 14, 27);
  const auto full = surface_shape(mesh, identity3(), HullPart::kCompute);
  const auto lean = surface_shape(mesh, identity3(), HullPart::kSkip);
  const auto diameter = surface_shape(mesh, identity3(), HullPart::kDiameterOnly);
  ASSERT_TRUE(full.ok() && lean.ok() && diameter.ok());
  expect_same_hull_free(*full, *lean);
  expect_hull_skipped(*lean);
  EXPECT_FALSE(std::isnan(full->maximum_3d_diameter_mm));
  // The diameter without the hull: the same value, the hull's fields skipped.
  expect_same_hull_free(*full, *diameter);
  expect_hull_skipped(*diameter, false);
  EXPECT_EQ(diameter->maximum_3d_diameter_mm, full->maximum_3d_diameter_mm);

  const auto grid = grid_around(mesh, {0.7, 0.7, 0.7}, 2);
  ASSERT_TRUE(grid.ok());
  const auto v = voxelize_1d(mesh, *grid);
  ASSERT_TRUE(v.ok());
  const auto sweep = mask_surface_sweep(v->volume);
  ASSERT_TRUE(sweep.ok());
  const auto mask_full = mask_surface_shape(*sweep, *grid, marching_cubes_table(), HullPart::kCompute);
  const auto mask_lean = mask_surface_shape(*sweep, *grid, marching_cubes_table(), HullPart::kSkip);
  const auto mask_diameter = mask_surface_shape(*sweep, *grid, marching_cubes_table(), HullPart::kDiameterOnly);
  ASSERT_TRUE(mask_full.ok() && mask_lean.ok() && mask_diameter.ok());
  expect_same_hull_free(*mask_full, *mask_lean);
  expect_hull_skipped(*mask_lean);
  expect_same_hull_free(*mask_full, *mask_diameter);
  expect_hull_skipped(*mask_diameter, false);
  EXPECT_EQ(mask_diameter->maximum_3d_diameter_mm, mask_full->maximum_3d_diameter_mm);
}

TEST(FeatureCatalogue, AReportFollowsTheCatalogueOrderAndHasNoHullValueUnlessAsked) {
  const TriangleMesh mesh = uv_sphere({0, 0, 0}, 8, 12, 24);
  const auto grid = grid_around(mesh, {1, 1, 1}, 2);
  ASSERT_TRUE(grid.ok());
  const auto v = voxelize_1d(mesh, *grid);
  ASSERT_TRUE(v.ok());
  const auto all = structure_features({v->volume, std::make_shared<const TriangleMesh>(mesh)}, FeatureRequest{});
  ASSERT_TRUE(all.ok()) << all.status().to_string();
  // Shape features come in catalogue order, the stored surface's before the mask's; the
  // coverage-weighted ones only when named.
  std::vector<std::string> expected;
  for (const FeatureDef& f : feature_catalogue())
    if (f.family != FeatureFamily::kIntensity && f.family != FeatureFamily::kDiameter2d &&
        !f.needs.has(FeatureNeed::kCoverage))
      expected.emplace_back(f.name);
  for (const FeatureDef& f : feature_catalogue())
    if (f.family == FeatureFamily::kSurface) expected.push_back(std::string(kMaskPrefix) + std::string(f.name));
  for (const FeatureDef& f : feature_catalogue())
    if (f.family == FeatureFamily::kDiameter2d) expected.emplace_back(f.name);
  std::vector<std::string> got;
  for (const Feature& f : all->features) got.push_back(f.name);
  EXPECT_EQ(got, expected);

  FeatureRequest lean;
  // The diameters alone are computed without the hulls (HullPart::kDiameterOnly): same values.
  lean.names = {"sphericity", "mask_surface_area_mm2", "maximum_3d_diameter_mm", "mask_maximum_3d_diameter_mm"};
  const auto some = structure_features({v->volume, std::make_shared<const TriangleMesh>(mesh)}, lean);
  ASSERT_TRUE(some.ok());
  ASSERT_EQ(some->features.size(), 4u);
  for (const Feature& f : some->features) {
    const auto same =
        std::find_if(all->features.begin(), all->features.end(), [&](const Feature& g) { return g.name == f.name; });
    ASSERT_NE(same, all->features.end());
    EXPECT_EQ(f.value, same->value) << f.name;  // bitwise, with or without the hull
  }
}

}  // namespace
}  // namespace soiq
