// Coverage-weighted intensity statistics: hand values, frequency-weight semantics, equality with the
// unweighted IBSI statistics at weight 1, and through structure_features on a sphere in a linear
// field, whose mean over the body is exactly the field at the body's centroid.
#include "core/features/weighted_intensity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>

#include "core/features/intensity_features.h"
#include "core/features/structure_features.h"
#include "core/geometry/primitives.h"
#include "core/geometry/surface_area_volume.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

TEST(WeightedIntensity, HandValues) {
  // Values 1 and 3 with weights 1 and 1/2: W = 3/2, mean = 5/3, variance = (4/9 + 8/9) / (3/2) = 8/9.
  auto f = weighted_intensity({1, 3}, {1, 0.5}, 2.0);
  ASSERT_TRUE(f.ok()) << f.status().to_string();
  EXPECT_DOUBLE_EQ(f->voxel_count, 1.5);
  EXPECT_DOUBLE_EQ(f->mean, 5.0 / 3);
  EXPECT_DOUBLE_EQ(f->variance, 8.0 / 9);
  EXPECT_DOUBLE_EQ(f->standard_deviation, std::sqrt(8.0 / 9));
  EXPECT_DOUBLE_EQ(f->root_mean_square, std::sqrt(11.0 / 3));
  EXPECT_DOUBLE_EQ(f->integrated_intensity, 2.5 * 2.0);
}

TEST(WeightedIntensity, WeightsAreFrequencies) {
  // Two half voxels of one value weigh as one whole voxel of it.
  auto split = weighted_intensity({4, 4, 10}, {0.5, 0.5, 1}, 1);
  auto whole = weighted_intensity({4, 10}, {1, 1}, 1);
  ASSERT_TRUE(split.ok() && whole.ok());
  EXPECT_DOUBLE_EQ(split->mean, whole->mean);
  EXPECT_DOUBLE_EQ(split->variance, whole->variance);
  EXPECT_DOUBLE_EQ(split->voxel_count, whole->voxel_count);
}

TEST(WeightedIntensity, WeightOneIsIbsisUnweightedStatistics) {
  std::vector<double> values;
  for (int i = 0; i < 1000; ++i) values.push_back(std::sin(i * 0.37) * 100 + 1000);
  auto w = weighted_intensity(values, std::vector<double>(values.size(), 1.0), 1);
  auto u = intensity_features(values);
  ASSERT_TRUE(w.ok() && u.ok());
  EXPECT_NEAR(w->mean, u->mean, 1e-12 * std::abs(u->mean));
  EXPECT_NEAR(w->variance, u->variance, 1e-9 * u->variance);
  EXPECT_NEAR(w->root_mean_square, u->root_mean_square, 1e-12 * u->root_mean_square);
  EXPECT_EQ(w->voxel_count, double(u->voxel_count));
}

TEST(WeightedIntensity, RefusesWhatIsNotAWeightedSample) {
  EXPECT_EQ(weighted_intensity({}, {}, 1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(weighted_intensity({1, 2}, {1}, 1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(weighted_intensity({1}, {0}, 1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(weighted_intensity({1}, {1.5}, 1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(weighted_intensity({NAN}, {1}, 1).status().code(), StatusCode::kInvalidArgument);
}

// A 1 cm sphere (radius 5 mm, off the lattice) on 2, 4 and 6 mm voxels, in the field
// I(p) = 100 + 3 x + 2 y - z: its mean over the sphere is I at the centre, exactly.
TEST(WeightedIntensity, MeanOverASmallSphereInALinearField) {
  const Vec3 c{1.37, -0.81, 2.29};
  const TriangleMesh sphere = uv_sphere(c, 5, 60, 120);
  const double field_at_centre = 100 + 3 * c[0] + 2 * c[1] - c[2];
  const double mesh_volume = surface_area_volume(sphere)->volume_mm3;
  for (double s : {2.0, 4.0, 6.0}) {
    ImageGeometry g;
    const int64_t n = int64_t(std::ceil(14 / s)) + 1;
    g.dims = {n, n, n};
    g.spacing_mm = {s, s, s};
    g.origin_mm = {-double(n - 1) * s / 2, -double(n - 1) * s / 2, -double(n - 1) * s / 2};
    Image field{g, std::vector<float>(size_t(g.voxel_count()))};
    for (int64_t k = 0; k < n; ++k)
      for (int64_t j = 0; j < n; ++j)
        for (int64_t i = 0; i < n; ++i) {
          const Vec3 p = g.index_to_physical({double(i), double(j), double(k)});
          field.voxels[size_t(i + n * (j + n * k))] = float(100 + 3 * p[0] + 2 * p[1] - p[2]);
        }
    auto v = voxelize_1d(sphere, g);
    ASSERT_TRUE(v.ok());
    StructureInput input{v->volume, std::make_shared<const TriangleMesh>(sphere)};
    FeatureRequest request;
    request.names = {"mean", "mean_w", "voxel_count_w", "volume_w_mm3", "integrated_intensity_w", "voxel_volume_mm3"};
    request.images = {{"field", &field}};
    auto r = structure_features(input, request);
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    std::map<std::string, double> f;
    for (const Feature& x : r->features) f[x.name] = x.value[0];
    std::printf(
        "%.0f mm voxels: mean %.4f  mean_w %.4f  field at centre %.4f;  volume %.2f  volume_w %.2f  mesh %.2f\n", s,
        f["mean"], f["mean_w"], field_at_centre, f["voxel_volume_mm3"], f["volume_w_mm3"], mesh_volume);
    // The weighted mean is the field's mean over the sampled body: within the field's change over
    // the sampling error of the volume (gradient |(3,2,-1)| = 3.74 per mm).
    EXPECT_NEAR(f["mean_w"], field_at_centre, 0.05 * s) << s;
    EXPECT_NEAR(f["volume_w_mm3"], mesh_volume, 0.03 * mesh_volume) << s;
    EXPECT_DOUBLE_EQ(f["voxel_count_w"] * s * s * s, f["volume_w_mm3"]);
    EXPECT_NEAR(f["integrated_intensity_w"], f["mean_w"] * f["volume_w_mm3"], 1e-9 * f["integrated_intensity_w"]);
  }
}

TEST(WeightedIntensity, OnlyWhenNamedAndOnlyWithASurface) {
  const TriangleMesh sphere = uv_sphere({0, 0, 0}, 5, 12, 24);
  ImageGeometry g;
  g.dims = {14, 14, 14};
  g.origin_mm = {-6.5, -6.5, -6.5};
  auto v = voxelize_1d(sphere, g);
  ASSERT_TRUE(v.ok());
  Image flat{g, std::vector<float>(size_t(g.voxel_count()), 7.f)};
  FeatureRequest every;
  every.images = {{"flat", &flat}};
  auto r = structure_features({v->volume, std::make_shared<const TriangleMesh>(sphere)}, every);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  for (const Feature& f : r->features) EXPECT_EQ(f.name.find("_w"), std::string::npos) << f.name << " not named";
  FeatureRequest named = every;
  named.names = {"mean_w"};
  r = structure_features({v->volume, nullptr}, named);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("surface model"), std::string::npos) << r.status().message();
  // A shell has no coverage weights: only the inside region answers mean_w.
  named.regions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 2}};
  r = structure_features({v->volume, std::make_shared<const TriangleMesh>(sphere)}, named);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->features.size(), 1u);
  EXPECT_EQ(r->features[0].region, "inside");
  EXPECT_DOUBLE_EQ(r->features[0].value[0], 7.0);
}

}  // namespace
}  // namespace soiq
