// Planar contours (RT Structure Set style) through the shared line filler, against hand counts.
#include "core/voxelize/fill_contours.h"

#include <gtest/gtest.h>

namespace soiq {
namespace {

ImageGeometry grid(int64_t n) {
  ImageGeometry g;
  g.dims = {n, n, n};
  return g;
}

PlanarContour square(double x0, double y0, double x1, double y1, double z, bool clockwise = false) {
  PlanarContour c;
  c.points_mm = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  if (clockwise) std::swap(c.points_mm[1], c.points_mm[3]);
  return c;
}

int64_t count(const std::vector<PlanarContour>& cs, FillRule rule = FillRule::kEvenOdd) {
  auto r = fill_contours(cs, grid(12), rule);
  EXPECT_TRUE(r.ok()) << r.status().to_string();
  return r.ok() ? voxel_count(r->volume) : -1;
}

TEST(FillContours, SquareCoversItsCentres) {
  // x in [1.5, 6.5] -> centres 2..6 (5), y in [2.5, 4.5] -> 3..4 (2).
  EXPECT_EQ(count({square(1.5, 2.5, 6.5, 4.5, 3)}), 10);
}

TEST(FillContours, HoleStaysAHoleWhateverItsOrientation) {
  const auto outer = square(0.5, 0.5, 8.5, 8.5, 4);
  EXPECT_EQ(count({outer, square(2.5, 2.5, 5.5, 5.5, 4)}), 64 - 9);
  EXPECT_EQ(count({outer, square(2.5, 2.5, 5.5, 5.5, 4, true)}), 64 - 9);
}

TEST(FillContours, KeyholeContourKeepsItsHole) {
  // One polygon: the outer square, a cut along y = 4.5... to the hole, around the hole the other
  // way, back along the same cut. The cut edges coincide, so the hole is still a hole.
  PlanarContour c;
  c.points_mm = {{0.5, 0.5, 2}, {8.5, 0.5, 2}, {8.5, 4.25, 2}, {5.5, 4.25, 2}, {5.5, 5.5, 2}, {2.5, 5.5, 2},
                 {2.5, 2.5, 2}, {5.5, 2.5, 2}, {5.5, 4.25, 2}, {8.5, 4.25, 2}, {8.5, 8.5, 2}, {0.5, 8.5, 2}};
  EXPECT_EQ(count({c}), 64 - 9);
}

TEST(FillContours, VertexOnARowLineIsCountedOnce) {
  // A diamond whose left and right vertices sit exactly on row y = 4.
  PlanarContour d;
  d.points_mm = {{4, 1, 5}, {7, 4, 5}, {4, 7, 5}, {1, 4, 5}};
  // Row j spans [1 + |j - 4|, 7 - |j - 4|): the left edge enters (inclusive), the right edge leaves
  // (exclusive). j = 1 and j = 7 only touch a vertex: an empty run.
  EXPECT_EQ(count({d}), 0 + 2 + 4 + 6 + 4 + 2);
}

TEST(FillContours, ContoursOnTheSameSliceCombineByXor) {
  EXPECT_EQ(count({square(0.5, 0.5, 4.5, 4.5, 1), square(2.5, 2.5, 6.5, 6.5, 1)}), 16 + 16 - 2 * 4);
  EXPECT_EQ(count({square(0.5, 0.5, 4.5, 4.5, 1), square(2.5, 2.5, 6.5, 6.5, 1)}, FillRule::kNonZero), 16 + 16 - 4);
}

TEST(FillContours, ContourBetweenSlicesIsRefused) {
  auto r = fill_contours({square(0.5, 0.5, 4.5, 4.5, 2.5)}, grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("slice plane"), std::string::npos);
}

TEST(FillContours, ContourOutsideTheGridIsCountedNotFilled) {
  auto r = fill_contours({square(0.5, 0.5, 4.5, 4.5, 40)}, grid(8));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->contours_outside_grid, 1);
  EXPECT_EQ(voxel_count(r->volume), 0);
}

TEST(FillContours, TooFewPointsIsInvalidArgument) {
  PlanarContour c;
  c.points_mm = {{1, 1, 1}, {2, 2, 1}};
  auto r = fill_contours({c}, grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("at least 3"), std::string::npos);
}

TEST(FillContours, ObliqueGridUsesItsOwnSlices) {
  // A grid rotated 90 degrees about z: index i runs along LPS y, j along -x.
  ImageGeometry g = grid(10);
  g.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  // In LPS: y in [1.5, 4.5] -> i = 2..4; x in [-6.5, -2.5] -> j = 3..6.
  auto r = fill_contours({square(-6.5, 1.5, -2.5, 4.5, 3)}, g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(r->volume), 3 * 4);
}

}  // namespace
}  // namespace soiq
