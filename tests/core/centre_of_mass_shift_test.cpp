// Centre of mass shift against hand-computed weighted centroids.
#include "core/features/centre_of_mass_shift.h"

#include <gtest/gtest.h>

#include <cmath>

namespace soiq {
namespace {

ImageGeometry row_grid() {
  ImageGeometry g;
  g.dims = {4, 1, 1};
  g.spacing_mm = {2, 1, 1};
  return g;
}

RunLengthVolume region(const ImageGeometry& g, std::vector<uint8_t> inside) {
  return from_mask(Mask{g, std::move(inside)});
}

TEST(CentreOfMassShift, UniformImageHasNoShift) {
  const auto g = row_grid();
  const auto shift = centre_of_mass_shift_mm(region(g, {0, 1, 1, 1}), Image{g, {5, 5, 5, 5}});
  ASSERT_TRUE(shift.ok());
  EXPECT_DOUBLE_EQ(*shift, 0);
}

TEST(CentreOfMassShift, HandComputedWeightedCentroid) {
  // Voxels i = 0, 1 (centres 0 and 2 mm) weighted 1 and 3: centroid 1 mm, weighted 1.5 mm.
  const auto g = row_grid();
  const auto shift = centre_of_mass_shift_mm(region(g, {1, 1, 0, 0}), Image{g, {1, 3, 100, 100}});
  ASSERT_TRUE(shift.ok());
  EXPECT_DOUBLE_EQ(*shift, 0.5);
}

TEST(CentreOfMassShift, ImageOnAnotherGridIsInvalidArgument) {
  const auto g = row_grid();
  auto other = g;
  other.origin_mm[0] = 1;
  const auto shift = centre_of_mass_shift_mm(region(g, {1, 1, 0, 0}), Image{other, {1, 1, 1, 1}});
  EXPECT_EQ(shift.status().code(), StatusCode::kInvalidArgument);
}

TEST(CentreOfMassShift, ZeroIntensitySumIsInvalidArgument) {
  const auto g = row_grid();
  const auto shift = centre_of_mass_shift_mm(region(g, {1, 1, 0, 0}), Image{g, {-2, 2, 0, 0}});
  EXPECT_EQ(shift.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(shift.status().message().find("sum to 0"), std::string::npos);
}

TEST(CentreOfMassShift, EmptyRegionIsInvalidArgument) {
  const auto g = row_grid();
  const auto shift = centre_of_mass_shift_mm(region(g, {0, 0, 0, 0}), Image{g, {1, 1, 1, 1}});
  EXPECT_EQ(shift.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(shift.status().message().find("empty region"), std::string::npos);
}

TEST(CentreOfMassShift, EqualsAVoxelByVoxelSumOnLongRuns) {
  // Runs of 1 to 13 voxels (every remainder of the four-way partial sums) on an anisotropic 3D grid.
  ImageGeometry g;
  g.dims = {13, 3, 2};
  g.spacing_mm = {0.7, 1.3, 2.5};
  g.origin_mm = {-5, 7, 11};
  std::vector<uint8_t> inside(size_t(g.voxel_count()), 0);
  std::vector<float> values(inside.size());
  double n = 0, w = 0, s[3] = {0, 0, 0}, sw[3] = {0, 0, 0};
  for (int64_t k = 0; k < 2; ++k) {
    for (int64_t j = 0; j < 3; ++j) {
      const int64_t length = 1 + (j + 3 * k) * 2;  // 1, 3, 5, ..., 11 voxels
      for (int64_t i = 0; i < 13; ++i) {
        const size_t at = size_t(i + 13 * (j + 3 * k));
        values[at] = float(1 + (i * 7 + j * 3 + k) % 5);
        if (i < length) {
          inside[at] = 1;
          n += 1, w += values[at];
          const double index[3] = {double(i), double(j), double(k)};
          for (int a = 0; a < 3; ++a) s[a] += index[a], sw[a] += values[at] * index[a];
        }
      }
    }
  }
  const Vec3 centroid = g.index_to_physical({s[0] / n, s[1] / n, s[2] / n});
  const Vec3 weighted = g.index_to_physical({sw[0] / w, sw[1] / w, sw[2] / w});
  const auto shift = centre_of_mass_shift_mm(region(g, inside), Image{g, values});
  ASSERT_TRUE(shift.ok()) << shift.status().to_string();
  EXPECT_NEAR(*shift, norm(centroid - weighted), 1e-12);
  EXPECT_GT(*shift, 0.01);
}

TEST(CentreOfMassShift, NonFiniteValueInsideIsInvalidArgumentNamingTheVoxel) {
  const auto g = row_grid();
  EXPECT_TRUE(centre_of_mass_shift_mm(region(g, {1, 1, 1, 0}), Image{g, {1, 2, 3, NAN}}).ok());  // outside: ignored
  const auto shift = centre_of_mass_shift_mm(region(g, {1, 1, 1, 0}), Image{g, {1, INFINITY, 3, 4}});
  EXPECT_EQ(shift.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(shift.status().message().find("voxel (1, 0, 0)"), std::string::npos) << shift.status().message();
}

TEST(CentreOfMassShift, ImageBufferOfWrongSizeIsInvalidArgument) {
  const auto g = row_grid();
  const auto shift = centre_of_mass_shift_mm(region(g, {1, 0, 0, 0}), Image{g, {1, 1}});
  EXPECT_EQ(shift.status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
