// A cohort's plot (render/plot_picture.h and the numbers behind it, render/plot_scales.h): bins by
// Freedman-Diaconis on data whose quartiles are known by hand, round ticks, the title's counts, a
// scatter's mark found at the pixel its value maps to, and the errors.
#include "render/plot_picture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/plot_scales.h"
#include "tests/render/decoded_picture.h"

namespace soiq::render {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(HistogramBins, FollowFreedmanDiaconis) {
  // 0..62 and 130, n = 64: quartiles at positions 15.75 and 47.25 are 15.75 and 47.25, IQR 31.5;
  // width 2 * 31.5 / 4 = 15.75; range 130: 8.25 bins, 9.
  std::vector<double> values;
  for (int i = 0; i < 63; ++i) values.push_back(i);
  values.push_back(130);
  EXPECT_EQ(histogram_bins(values), 9);
}

TEST(HistogramBins, StayWithinFiveToFifty) {
  // 0..63: width 15.75 over a range of 63 is 4 bins, raised to 5.
  std::vector<double> even;
  for (int i = 0; i < 64; ++i) even.push_back(i);
  EXPECT_EQ(histogram_bins(even), 5);
  // 0..24, 1000, 1001 (n = 27): IQR 13, width 8.67 over 1001: 116 bins, capped at 50.
  std::vector<double> outliers;
  for (int i = 0; i < 25; ++i) outliers.push_back(i);
  outliers.push_back(1000);
  outliers.push_back(1001);
  EXPECT_EQ(histogram_bins(outliers), 50);
  EXPECT_EQ(histogram_bins({}), 5);
  EXPECT_EQ(histogram_bins({3}), 5);
  EXPECT_EQ(histogram_bins({3, 3, 3}), 5);
}

TEST(HistogramBins, UseSturgesWhenTheInterquartileRangeIsZero) {
  // 98 values of 5, a 6 and a 7: no IQR; ceil(log2 100) + 1 = 8.
  std::vector<double> values(98, 5);
  values.push_back(6);
  values.push_back(7);
  EXPECT_EQ(histogram_bins(values), 8);
}

TEST(RoundTicks, AreMultiplesOfOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_EQ(round_ticks(0, 100, 5), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  EXPECT_EQ(round_ticks(-3, 47, 5), (std::vector<double>{0, 10, 20, 30, 40}));
  EXPECT_EQ(round_ticks(-3, 47, 10), (std::vector<double>{0, 5, 10, 15, 20, 25, 30, 35, 40, 45}));
  EXPECT_EQ(round_ticks(1200, 9100, 4), (std::vector<double>{2000, 4000, 6000, 8000}));
  const std::vector<double> small = round_ticks(0.013, 0.058, 5);  // step 0.009 rounded up to 0.01
  ASSERT_EQ(small.size(), 4u);
  EXPECT_EQ(tick_label(small[0]), "0.02");
  EXPECT_EQ(tick_label(small[3]), "0.05");
  // Counts: never a step under 1.
  EXPECT_EQ(round_ticks(0, 3, 6, 1), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(round_ticks(4, 4, 5), (std::vector<double>{4}));
  EXPECT_TRUE(round_ticks(5, 4, 5).empty());
  EXPECT_TRUE(round_ticks(0, kNaN, 5).empty());
  for (double t : round_ticks(-1, 1, 4)) EXPECT_FALSE(std::signbit(t) && t == 0);
}

TEST(TickLabel, IsTheShortestTextOfTheValue) {
  EXPECT_EQ(tick_label(0.1 * 3), "0.3");
  EXPECT_EQ(tick_label(1500), "1500");
  EXPECT_EQ(tick_label(-2.5), "-2.5");
  EXPECT_EQ(tick_label(0), "0");
  EXPECT_EQ(tick_label(2.5e-5), "2.5e-05");
}

TEST(PlotTitle, CountsTheRowsPlottedAndThoseWithoutAValue) {
  EXPECT_EQ(plot_title("volume", 48, 2), "volume \u2014 48 rows, 2 without a value");
  EXPECT_EQ(plot_title("", 48, 0), "48 rows");
  EXPECT_EQ(plot_title("", 1, 0), "1 row");
  EXPECT_EQ(plot_title("", 0, 3), "0 rows, 3 without a value");
  EXPECT_EQ(axis_label("voxel_volume_mm3", "mm3"), "voxel_volume_mm3 (mm3)");
  EXPECT_EQ(axis_label("sphericity", ""), "sphericity");
}

testing::DecodedPicture plot(const std::vector<PlotAxis>& axes, int width, int height, const std::string& keep = "") {
  const Result<std::string> png = plot_picture(axes, "cohort", width, height, PictureOptions{});
  EXPECT_TRUE(png.ok()) << png.status().to_string();
  if (!png.ok()) return {};
  if (!keep.empty()) testing::keep_picture(keep, *png);
  return testing::decode_png(*png);
}

bool is_mark(const Rgb& c) { return c.b > c.r + 60 && c.b > 150; }  // the marks' blue, over white or grid grey

TEST(PlotPicture, AHistogramDecodesToItsSizeWithBarsInTheFrame) {
  PlotAxis volume{"voxel_volume_mm3", "mm3", {}};
  for (int i = 0; i < 200; ++i) volume.values.push_back(3000 + 40 * std::sin(i * 0.7) * (i % 17));
  volume.values.push_back(kNaN);
  const testing::DecodedPicture p = plot({volume}, 640, 480, "plot_histogram.png");
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.width, 640);
  EXPECT_EQ(p.height, 480);
  // Bars are drawn, and only inside the frame.
  const PlotFrame f = plot_frame(640, 480);
  int bar_pixels = 0, stray = 0;
  for (int y = 0; y < p.height; ++y) {
    for (int x = 0; x < p.width; ++x) {
      if (!is_mark(p.at(x, y))) continue;
      ++bar_pixels;
      stray += x < f.left - 1 || x > f.right + 1 || y < f.top - 1 || y > f.bottom + 1;
    }
  }
  EXPECT_GT(bar_pixels, 1000);
  EXPECT_EQ(stray, 0);
}

TEST(PlotPicture, AScatterPutsEachMarkWhereItsValuesMapTo) {
  // x in 0..10 and y in 0..20, padded by 5 % of the range: x spans -0.5..10.5, y -1..21.
  const PlotAxis x{"volume", "mm3", {0, 10, 5, 2, kNaN}}, y{"mean[inside,CT]", "HU", {0, 20, 10, 16, 3}};
  const testing::DecodedPicture p = plot({x, y}, 600, 400, "plot_scatter.png");
  ASSERT_TRUE(p.ok);
  const PlotFrame f = plot_frame(600, 400);
  const auto at = [&](double vx, double vy) {
    return std::pair<int, int>(static_cast<int>(f.left + (vx + 0.5) / 11 * (f.right - f.left)),
                               static_cast<int>(f.bottom - (vy + 1) / 22 * (f.bottom - f.top)));
  };
  for (const auto& [vx, vy] : std::vector<std::pair<double, double>>{{0, 0}, {10, 20}, {5, 10}, {2, 16}}) {
    const auto [px, py] = at(vx, vy);
    EXPECT_TRUE(is_mark(p.at(px, py))) << vx << "," << vy << " at " << px << "," << py;
  }
  // Where no row is, no mark (the row without an x value is left out).
  for (const auto& [vx, vy] : std::vector<std::pair<double, double>>{{8, 3}, {9, 2}}) {
    const auto [px, py] = at(vx, vy);
    EXPECT_FALSE(is_mark(p.at(px, py))) << vx << "," << vy;
  }
}

TEST(PlotPicture, NoFiniteValueGivesEmptyAxesNotAnError) {
  const testing::DecodedPicture p = plot({PlotAxis{"sphericity", "", {kNaN, kNaN}}}, 300, 200);
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.width, 300);
}

TEST(PlotPicture, SvgAndJpegToo) {
  const PlotAxis volume{"volume", "mm3", {1, 2, 3, 4, 5, 6}};
  const Result<std::string> svg = plot_picture({volume}, "", 400, 300, PictureOptions{PictureFormat::kSvg});
  ASSERT_TRUE(svg.ok());
  EXPECT_EQ(svg->rfind("<?xml", 0), 0u);
  const Result<std::string> jpeg = plot_picture({volume}, "", 400, 300, PictureOptions{PictureFormat::kJpeg, 80});
  ASSERT_TRUE(jpeg.ok());
  const testing::DecodedPicture p = testing::decode_jpeg(*jpeg);
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.width, 400);
  EXPECT_EQ(p.height, 300);
}

void expect_plot_refused(const Result<std::string>& r, const std::string& phrase) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find(phrase), std::string::npos) << r.status().message();
}

TEST(PlotPicture, RefusesOtherThanOneOrTwoAxesMismatchedLengthsAndBadSizes) {
  const PlotAxis a{"a", "", {1, 2, 3}}, b{"b", "", {1, 2, 3, 4}};
  expect_plot_refused(plot_picture({}, "", 400, 300, PictureOptions{}),
                      "1 feature (a histogram) or 2 (a scatter), not 0");
  expect_plot_refused(plot_picture({a, a, a}, "", 400, 300, PictureOptions{}), "not 3");
  expect_plot_refused(plot_picture({a, b}, "", 400, 300, PictureOptions{}), "3 and 4 values");
  expect_plot_refused(plot_picture({a}, "", 199, 300, PictureOptions{}), "200..8192");
  expect_plot_refused(plot_picture({a}, "", 400, kMaxPictureSide + 1, PictureOptions{}), "200..8192");
}

}  // namespace
}  // namespace soiq::render
