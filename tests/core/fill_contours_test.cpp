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

TEST(FillContours, ContourMidwayBetweenSlicesIsRefusedWithItsDistance) {
  auto r = fill_contours({square(0.5, 0.5, 4.5, 4.5, 2.5)}, grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find(
                "contour 0 lies 0.5 mm from the nearest image plane (slice 3), more than 0.45 mm (0.45 of"),
            std::string::npos)
      << r.status().message();
}

TEST(FillContours, ContourOffItsPlaneGoesToTheNearestPlane) {
  // 0.3 of the 3 mm spacing above slice 1 (z = 3): filled on slice 1, as the contour at z = 3 is.
  ImageGeometry g = grid(8);
  g.spacing_mm = {1, 1, 3};
  auto off = fill_contours({square(0.5, 0.5, 4.5, 4.5, 3.9)}, g);
  auto on = fill_contours({square(0.5, 0.5, 4.5, 4.5, 3.0)}, g);
  ASSERT_TRUE(off.ok() && on.ok()) << off.status().to_string();
  EXPECT_EQ(off->volume.runs, on->volume.runs);
  EXPECT_EQ(voxel_count(off->volume), 16);
}

TEST(FillContours, ANonPlanarContourIsRefusedWithItsLargestDistanceInMm) {
  // One corner 2 mm above the others: measured from the plane the other points lie on.
  PlanarContour c = square(0.5, 0.5, 4.5, 4.5, 3);
  c.points_mm.push_back({2.5, 5.5, 3});
  c.points_mm[2][2] = 5;
  auto r = fill_contours({c}, grid(8));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("contour 0 is not planar: a point lies 2 mm from the contour's plane"),
            std::string::npos)
      << r.status().message();
  c.points_mm[2][2] = 3.05;  // within the tolerance (0.1 mm)
  EXPECT_TRUE(fill_contours({c}, grid(8)).ok());
}

TEST(FillContours, ContoursOfAFinerSeriesKeepTheNearestPlanePerSlice) {
  // Outlines drawn every 1 mm on a 3 mm series: slice 1 (z = 3) is reached by those at z = 2, 3
  // and 4; it keeps the one at z = 3 (XOR of the three would leave one copy, of the wrong size).
  ImageGeometry g = grid(8);
  g.spacing_mm = {1, 1, 3};
  auto r =
      fill_contours({square(0.5, 0.5, 2.5, 2.5, 2), square(0.5, 0.5, 4.5, 4.5, 3), square(0.5, 0.5, 6.5, 6.5, 4)}, g);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(voxel_count(r->volume), 16);
  EXPECT_EQ(r->contours_superseded, 2);
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
