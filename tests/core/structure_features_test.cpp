// The features entry point: what it computes, under which names, from which surface, and each
// bad request answered clearly. The values themselves are proven part by part (volume_shape,
// surface_shape, regions, intensity_features tests); here the IBSI phantom checks the wiring.
#include "core/features/structure_features.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>

#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

const std::string kData = SOIQ_TEST_DATA_DIR;

std::map<std::string, double> by_name(const FeatureReport& r, const std::string& region = "") {
  std::map<std::string, double> m;
  for (const Feature& f : r.features) {
    if (f.region == region && !f.value.empty()) m[f.name] = f.value[0];
  }
  return m;
}

FeatureRequest asking_for(std::vector<std::string> names) {
  FeatureRequest r;
  r.names = std::move(names);
  return r;
}

struct Phantom {
  StructureInput structure;
  Image image;
};

Phantom phantom() {
  auto image = read_image(kData + "/ibsi_digital_phantom/phantom.nii.gz");
  auto mask = read_image(kData + "/ibsi_digital_phantom/mask.nii.gz");
  EXPECT_TRUE(image.ok() && mask.ok());
  Phantom p;
  p.structure.volume = from_mask(mask_from_image(*mask));
  p.image = *image;
  return p;
}

// A UV sphere of radius 10 mm (segments x 2 segments) as a stored surface, with its voxels on an
// n^3 grid of 1 mm around it.
StructureInput sphere_structure(int segments, int64_t n) {
  const TriangleMesh sphere = uv_sphere({0.2, 0.1, -0.3}, 10, segments, 2 * segments);
  ImageGeometry g;
  g.dims = {n, n, n};
  const double o = -double(n / 2);
  g.origin_mm = {o, o, o};
  auto v = voxelize_1d(sphere, g);
  EXPECT_TRUE(v.ok()) << v.status().to_string();
  return {v.ok() ? v->volume : empty_volume(g), std::make_shared<const TriangleMesh>(sphere)};
}

TEST(StructureFeatures, IbsiPhantomThroughTheEntryPoint) {
  const Phantom p = phantom();
  FeatureRequest request;
  request.images = {{"phantom", &p.image}};
  request.covariance = CovarianceDivisor::kNMinus1;  // as the IBSI consensus values were computed
  auto r = structure_features(p.structure, request);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const auto shape = by_name(*r);
  const auto inside = by_name(*r, "inside");
  // Value +- tolerance from the IBSI reference manual (REFERENCE_VALUES.md).
  EXPECT_NEAR(shape.at("mesh_volume_mm3"), 556, 4);
  EXPECT_NEAR(shape.at("voxel_volume_mm3"), 592, 4);
  EXPECT_NEAR(shape.at("surface_area_mm2"), 388, 3);
  EXPECT_NEAR(shape.at("sphericity"), 0.843, 0.005);
  EXPECT_NEAR(shape.at("maximum_3d_diameter_mm"), 13.1, 0.1);
  EXPECT_NEAR(shape.at("minor_axis_length_mm"), 9.31, 0.06);
  EXPECT_NEAR(shape.at("volume_density_convex_hull"), 0.961, 0.006);
  EXPECT_NEAR(inside.at("mean"), 2.15, 0.005);
  EXPECT_NEAR(inside.at("excess_kurtosis"), -0.355, 0.001);
  EXPECT_NEAR(inside.at("centre_of_mass_shift_mm"), 0.672, 0.004);
  // Every name is reported once per block when none is asked for.
  for (const std::string& n : shape_feature_names()) EXPECT_EQ(shape.count(n), 1u) << n;
  for (const std::string& n : intensity_feature_names()) EXPECT_EQ(inside.count(n), 1u) << n;
}

TEST(StructureFeatures, ComputesOnlyWhatIsAskedAndTimesEachPart) {
  const Phantom p = phantom();
  FeatureRequest request;
  request.names = {"voxel_count", "elongation"};
  auto r = structure_features(p.structure, request);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->features.size(), 2u);
  EXPECT_EQ(r->features[0].name, "voxel_count");
  EXPECT_EQ(r->features[0].value, std::vector<double>{74});
  ASSERT_EQ(r->timings_ms.size(), 1u);  // no marching cubes for volume features
  EXPECT_EQ(r->timings_ms[0].first, "volume shape");
}

TEST(StructureFeatures, SurfaceModelValuesAndMaskSurfaceValuesAreNamedApart) {
  // A finely meshed sphere of radius 10 mm: the stored surface has nearly the analytic volume;
  // the mask's marching-cubes surface on a 1 mm grid is a coarser approximation.
  const StructureInput s = sphere_structure(100, 25);
  FeatureRequest request;
  request.names = {"mesh_volume_mm3", "mask_mesh_volume_mm3"};
  auto r = structure_features(s, request);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const auto m = by_name(*r);
  const double analytic = 4.0 / 3.0 * 3.14159265358979 * 1000;
  // The inscribed 100x200 UV sphere loses about 3 (1 - cos(pi/100)) ~ 1.5e-3 of the volume.
  EXPECT_NEAR(m.at("mesh_volume_mm3"), analytic, 2e-3 * analytic);
  EXPECT_NE(m.at("mask_mesh_volume_mm3"), m.at("mesh_volume_mm3"));
  EXPECT_NEAR(m.at("mask_mesh_volume_mm3"), analytic, 0.05 * analytic);
}

// With threads > 1 the independent parts run at once; the report must not notice: the same
// features in the same order with bitwise the same values, and the same parts timed, in order.
TEST(StructureFeatures, ThreadCountChangesNothingInTheReport) {
  const StructureInput s = sphere_structure(60, 30);
  Image ramp;
  ramp.geometry = s.volume.geometry;
  for (int64_t n = 0; n < ramp.geometry.voxel_count(); ++n) ramp.voxels.push_back(float((n * 7919) % 1000) / 10.0f);
  FeatureRequest request;
  request.images = {{"ramp", &ramp}, {"ramp again", &ramp}};
  request.regions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 2}, RegionSpec{RegionKind::kCore, 3}};
  auto one = structure_features(s, request);
  ASSERT_TRUE(one.ok()) << one.status().to_string();
  // volume, stored surface, mask_ surface, 2D diameters, and 17 + 16 + 16 per image for the regions.
  ASSERT_EQ(one->features.size(), 9u + 13u + 13u + 3u + 2 * (17u + 16u + 16u));
  // In the documented order: shape, then region by region (named as parse_region reads them), image
  // by image.
  EXPECT_EQ(one->features[0].name, "voxel_count");
  EXPECT_EQ(one->features[9].name, "mesh_volume_mm3");
  EXPECT_EQ(one->features[22].name, "mask_mesh_volume_mm3");
  EXPECT_EQ(one->features[35].name, "maximum_2d_diameter_slice_mm");
  EXPECT_EQ(one->features[38].name + "/" + one->features[38].region + "/" + one->features[38].image,
            "mean/inside/ramp");
  EXPECT_EQ(one->features.back().region + "/" + one->features.back().image, "core:3/ramp again");
  for (const int threads : {2, 4}) {
    request.threads = threads;
    auto many = structure_features(s, request);
    ASSERT_TRUE(many.ok()) << many.status().to_string();
    ASSERT_EQ(many->features.size(), one->features.size()) << threads;
    for (size_t i = 0; i < one->features.size(); ++i) {
      const Feature &a = one->features[i], &b = many->features[i];
      EXPECT_EQ(a.name + "/" + a.region + "/" + a.image, b.name + "/" + b.region + "/" + b.image) << threads;
      EXPECT_EQ(a.value, b.value) << a.name << " " << a.region << " " << a.image << " threads " << threads;
    }
    ASSERT_EQ(many->timings_ms.size(), one->timings_ms.size());
    for (size_t i = 0; i < one->timings_ms.size(); ++i) {
      EXPECT_EQ(many->timings_ms[i].first, one->timings_ms[i].first);
    }
  }
  // An error is the one a single thread reports: the first failing part in report order (here
  // the image is missing in the first region's section and the core is empty in the last).
  request.images = {{"missing", nullptr}};
  request.regions = {RegionSpec{}, RegionSpec{RegionKind::kCore, 50}};
  for (const int threads : {1, 2, 4}) {
    request.threads = threads;
    auto r = structure_features(s, request);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().message(), "image 'missing' was not given") << threads;
  }
}

TEST(StructureFeatures, UnknownFeatureIsInvalidArgumentListingTheKnownOnes) {
  auto r = structure_features(phantom().structure, asking_for({"volume_in_litres"}));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("unknown feature 'volume_in_litres'"), std::string::npos);
  EXPECT_NE(r.status().message().find("sphericity"), std::string::npos);
}

TEST(StructureFeatures, MaskPrefixNeedsAStoredSurface) {
  auto r = structure_features(phantom().structure, asking_for({"mask_sphericity"}));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("this structure has none: ask for 'sphericity'"), std::string::npos)
      << r.status().message();
}

TEST(StructureFeatures, IntensityWithoutAnImageIsInvalidArgument) {
  auto r = structure_features(phantom().structure, asking_for({"mean"}));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("need an image"), std::string::npos);
}

TEST(StructureFeatures, ImageInAnotherFrameOfReferenceIsInvalidArgument) {
  Phantom p = phantom();
  p.image.geometry.origin_mm = {500, 500, 500};  // nowhere near the structure
  FeatureRequest request;
  request.names = {"mean"};
  request.images = {{"moved", &p.image}};
  auto r = structure_features(p.structure, request);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("frame of reference"), std::string::npos) << r.status().message();
}

TEST(StructureFeatures, EmptyRegionIsInvalidArgument) {
  Phantom p = phantom();
  FeatureRequest request;
  request.names = {"mean"};
  request.images = {{"phantom", &p.image}};
  request.regions = {RegionSpec{RegionKind::kCore, 50}};  // deeper than the phantom is thick
  auto r = structure_features(p.structure, request);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("empty"), std::string::npos);
}

// The report keys intensity features by region and image name: a name twice would put two values
// under one key, so it is refused, naming the duplicate.
TEST(StructureFeatures, ImageOrRegionNamedTwiceIsInvalidArgument) {
  Phantom p = phantom();
  FeatureRequest request;
  request.names = {"mean"};
  request.images = {{"PET", &p.image}, {"PET", &p.image}};
  auto r = structure_features(p.structure, request);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("image name 'PET' is given twice"), std::string::npos) << r.status().message();
  request.images = {{"PET", &p.image}};
  request.regions = {RegionSpec{RegionKind::kShell, 2}, RegionSpec{}, RegionSpec{RegionKind::kShell, 2.0}};
  r = structure_features(p.structure, request);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("region shell:2 is asked twice"), std::string::npos) << r.status().message();
}

TEST(StructureFeatures, ImageThatIsNaNOverTheWholeRegionIsInvalidArgumentSayingSo) {
  Phantom p = phantom();
  for (float& v : p.image.voxels) v = std::numeric_limits<float>::quiet_NaN();
  FeatureRequest request;
  request.names = {"mean"};
  request.images = {{"broken", &p.image}};
  auto r = structure_features(p.structure, request);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("'broken' is NaN or infinite at every voxel of region inside (74 voxels)"),
            std::string::npos)
      << r.status().message();
}

TEST(StructureFeatures, EmptyStructureIsInvalidArgument) {
  StructureInput s;
  ImageGeometry g;
  g.dims = {4, 4, 4};
  s.volume = empty_volume(g);
  auto r = structure_features(s, FeatureRequest{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("no voxels"), std::string::npos);
}

}  // namespace
}  // namespace soiq
