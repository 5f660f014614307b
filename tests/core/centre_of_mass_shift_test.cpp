// Centre of mass shift against hand-computed weighted centroids.
#include "core/centre_of_mass_shift.h"

#include <gtest/gtest.h>

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

TEST(CentreOfMassShift, ImageBufferOfWrongSizeIsInvalidArgument) {
  const auto g = row_grid();
  const auto shift = centre_of_mass_shift_mm(region(g, {1, 0, 0, 0}), Image{g, {1, 1}});
  EXPECT_EQ(shift.status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
