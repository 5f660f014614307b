// The grid of a slice stack from positions and orientation, and each stack it must refuse.
#include "dicom/slice_stack.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace soiq::dicom {
namespace {

// n slices of 4x3 pixels (0.5 mm between columns, 0.7 between rows) along the normal of
// `orientation`, `step` mm apart, starting at `origin`.
std::vector<SliceInfo> stack(int n, double step, std::array<double, 6> orientation = {1, 0, 0, 0, 1, 0},
                             Vec3 origin = {-10, 20, 30}) {
  const Vec3 row{orientation[0], orientation[1], orientation[2]}, col{orientation[3], orientation[4], orientation[5]};
  const Vec3 normal = cross(row, col);
  std::vector<SliceInfo> out;
  for (int k = 0; k < n; ++k) {
    SliceInfo s;
    s.position_mm = origin + (k * step) * normal;
    s.orientation = orientation;
    s.pixel_spacing_mm = {0.7, 0.5};
    s.rows = 3;
    s.columns = 4;
    s.label = "#" + std::to_string(k + 1);
    out.push_back(s);
  }
  return out;
}

TEST(SliceStack, SortsSlicesAlongTheNormalAndTakesSpacingFromPositions) {
  auto slices = stack(4, 2.5);
  std::swap(slices[0], slices[3]);
  auto r = slice_stack(slices, /*single_slice_spacing_mm=*/9);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->order, (std::vector<size_t>{3, 1, 2, 0}));
  const ImageGeometry& g = r->geometry;
  EXPECT_EQ(g.dims, (std::array<int64_t, 3>{4, 3, 4}));
  EXPECT_EQ(g.spacing_mm, (Vec3{0.5, 0.7, 2.5}));
  EXPECT_EQ(g.origin_mm, (Vec3{-10, 20, 30}));
  EXPECT_EQ(g.direction, identity3());
}

TEST(SliceStack, ObliqueOrientationGivesItsDirectionColumns) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  auto r = slice_stack(stack(3, 2, {c, s, 0, 0, 0, -1}));
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const Mat3& d = r->geometry.direction;
  EXPECT_EQ((Vec3{d[0][0], d[1][0], d[2][0]}), (Vec3{c, s, 0}));
  EXPECT_EQ((Vec3{d[0][1], d[1][1], d[2][1]}), (Vec3{0, 0, -1}));
  const Vec3 n = cross({c, s, 0}, {0, 0, -1});
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(d[i][2], n[i]);
  EXPECT_NEAR(r->geometry.spacing_mm[2], 2, 1e-12);
}

TEST(SliceStack, SingleSliceTakesTheGivenSpacing) {
  auto r = slice_stack(stack(1, 0), 5);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->geometry.spacing_mm[2], 5);
}

TEST(SliceStack, MissingSliceIsNamedWithItsNeighbours) {
  auto slices = stack(6, 3);
  slices.erase(slices.begin() + 2);
  auto r = slice_stack(slices);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("1 missing slice(s) between #2 at (-10, 20, 33) and #4 at (-10, 20, 39)"),
            std::string::npos)
      << r.status().message();
  // A run of longer steps is a protocol, not a lost file.
  slices = stack(6, 3);
  slices[4].position_mm[2] += 3;
  slices[5].position_mm[2] += 6;
  r = slice_stack(slices);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_TRUE(r->geometry.uneven());
}

// Uneven spacing (a protocol finer in the middle, the end slices further off): each slice where it
// is, so every voxel centre is its slice's own pixel.
TEST(SliceStack, UnevenSpacingKeepsEverySlicesPosition) {
  auto slices = stack(6, 0);
  const double z[6] = {0, 4, 6.5, 9, 11.5, 16.7};
  for (int k = 0; k < 6; ++k) slices[k].position_mm[2] = 30 + z[k];
  std::swap(slices[0], slices[4]);
  auto r = slice_stack(slices);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const ImageGeometry& g = r->geometry;
  ASSERT_TRUE(g.uneven());
  ASSERT_EQ(g.slice_positions_mm.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(g.slice_positions_mm[size_t(k)], z[k], 1e-12);
  EXPECT_NEAR(g.spacing_mm[2], 16.7 / 5, 1e-12);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(g.index_to_physical({2, 1, double(k)})[2], 30 + z[k], 1e-12);
    EXPECT_NEAR(g.physical_to_index({-9, 20.7, 30 + z[k]})[2], k, 1e-12);
  }
  // Between slices the index runs linearly: a quarter of the way from 9 to 11.5 mm is k = 3.25.
  EXPECT_NEAR(g.physical_to_index({-10, 20, 39.625})[2], 3.25, 1e-12);
  // Voxels reach halfway to each neighbour: slice 1 from 2 to 5.25 mm, the last as far out as in.
  EXPECT_NEAR(g.voxel_volume_mm3(1), 0.5 * 0.7 * 3.25, 1e-12);
  EXPECT_NEAR(g.voxel_volume_mm3(5), 0.5 * 0.7 * 5.2, 1e-12);
  EXPECT_NE(describe(g).find("unevenly spaced slices 2.5 to 5.2 mm apart"), std::string::npos) << describe(g);
}

TEST(SliceStack, UnevenAndTiltedStackKeepsBoth) {
  auto slices = stack(5, 0);
  const double z[5] = {0, 2, 4, 7, 10};
  for (int k = 0; k < 5; ++k) slices[k].position_mm = slices[k].position_mm + Vec3{0, 0.4 * z[k], z[k]};
  auto r = slice_stack(slices);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const ImageGeometry& g = r->geometry;
  ASSERT_TRUE(g.uneven() && g.sheared());
  for (int k = 0; k < 5; ++k) {
    const Vec3 p = g.index_to_physical({1, 2, double(k)});
    const Vec3 want = slices[k].position_mm + Vec3{0.5, 1.4, 0};
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(p[a], want[a], 1e-12) << "slice " << k;
  }
}

TEST(SliceStack, TwoSlicesAtOnePositionAreRefused) {
  auto slices = stack(3, 3);
  slices[2].position_mm = slices[1].position_mm;
  auto r = slice_stack(slices);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("same position"), std::string::npos) << r.status().message();
}

TEST(SliceStack, InconsistentOrientationOrSizeIsNamed) {
  auto slices = stack(3, 3);
  slices[1].orientation = {0, 1, 0, 1, 0, 0};
  auto r = slice_stack(slices);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("slice #2 has a different Image Orientation"), std::string::npos);
  slices = stack(3, 3);
  slices[2].rows = 5;
  r = slice_stack(slices);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("slice #3 is 4x5"), std::string::npos) << r.status().message();
}

// Gantry tilt: each slice shifted in-plane by the same step. The grid is sheared so that every
// voxel centre is its slice's own pixel centre, never resampled.
TEST(SliceStack, TiltedStackGetsAShearedGridThroughEverySlicesOwnPixels) {
  const std::array<double, 6> oblique = {0.8, 0.6, 0, 0, 0, -1};  // rows and columns not on the LPS axes
  auto slices = stack(5, 2.5, oblique);
  const Vec3 row{0.8, 0.6, 0}, col{0, 0, -1};
  const Vec3 shift = 0.9 * row + (-0.4) * col;  // per slice, in-plane: tilt atan(0.985 / 2.5) = 21.5 degrees
  for (int k = 0; k < 5; ++k) slices[k].position_mm = slices[k].position_mm + double(k) * shift;
  std::swap(slices[1], slices[4]);
  auto r = slice_stack(slices);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const ImageGeometry& g = r->geometry;
  ASSERT_TRUE(g.sheared());
  EXPECT_NEAR(g.slice_distance_mm(), 2.5, 1e-12);
  EXPECT_NEAR(g.spacing_mm[2], std::sqrt(2.5 * 2.5 + 0.81 + 0.16), 1e-12);
  EXPECT_NEAR(g.tilt_degrees(), std::atan(std::sqrt(0.97) / 2.5) * 180 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(g.voxel_volume_mm3(), 0.5 * 0.7 * 2.5, 1e-12);
  for (size_t k = 0; k < 5; ++k) {
    const SliceInfo& s = slices[r->order[k]];
    // Pixel (column 3, row 2) of slice k, from its own position: the grid's voxel (3, 2, k).
    const Vec3 pixel = s.position_mm + (3 * 0.5) * row + (2 * 0.7) * col;
    const Vec3 centre = g.index_to_physical({3, 2, double(k)});
    const Vec3 back = g.physical_to_index(pixel);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(centre[a], pixel[a], 1e-12) << "slice " << k;
      EXPECT_NEAR(back[a], (Vec3{3, 2, double(k)})[a], 1e-12) << "slice " << k;
    }
  }
  // The orthonormal frame of the slices: rows, columns and their normal on k's side.
  const Mat3 f = g.frame();
  const Vec3 n = cross(row, col);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(f[a][2], n[a], 1e-12);
}

TEST(SliceStack, DriftTooSmallPerStepToSeeStillMakesATiltedGridOnceItAddsUp) {
  auto slices = stack(40, 1);
  for (int k = 0; k < 40; ++k) slices[k].position_mm[1] += 0.008 * k;  // 8 um per slice, 0.3 mm in all
  auto r = slice_stack(slices);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_TRUE(r->geometry.sheared());
  EXPECT_NEAR(r->geometry.index_to_physical({0, 0, 39})[1], 20 + 0.008 * 39, 1e-12);
}

TEST(SliceStack, StackTiltedByMoreThanOneAngleOrTooFarIsRefusedNamingTheSlice) {
  auto slices = stack(4, 3);
  for (int k = 0; k < 4; ++k) slices[k].position_mm[1] += 0.5 * k;
  slices[2].position_mm[0] += 0.2;  // one slice off the tilted line
  auto r = slice_stack(slices);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("slice #3"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("nor tilted by one angle"), std::string::npos) << r.status().message();
  slices = stack(3, 1);
  for (int k = 0; k < 3; ++k) slices[k].position_mm[0] += 2 * k;  // 63 degrees
  r = slice_stack(slices);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("63.4 degrees"), std::string::npos) << r.status().message();
}

TEST(SliceStack, NonFinitePositionOfAnySliceIsRefusedNamingItAndTheTag) {
  // A NaN passes every "<=" test: without its own check it broke the sort and reached the grid.
  for (double bad : {std::nan(""), HUGE_VAL, 1e7}) {
    auto slices = stack(4, 2);
    slices[2].position_mm[2] = bad;
    auto r = slice_stack(slices);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find("slice #3: Image Position (Patient) (0020,0032)"), std::string::npos)
        << r.status().message();
  }
}

TEST(SliceStack, NonFiniteOrOversizedPixelSpacingIsRefusedNamingTheTag) {
  for (double bad : {std::nan(""), HUGE_VAL, 0.0, -0.5, 2e3}) {
    auto slices = stack(1, 1);
    slices[0].pixel_spacing_mm[1] = bad;
    auto r = slice_stack(slices);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find("slice #1: Pixel Spacing (0028,0030)"), std::string::npos)
        << r.status().message();
  }
}

TEST(SliceStack, SingleSliceWithANonFiniteSpacingTakesOneMillimetre) {
  auto r = slice_stack(stack(1, 1), HUGE_VAL);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->geometry.spacing_mm[2], 1);
}

}  // namespace
}  // namespace soiq::dicom
