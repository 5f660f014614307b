// Windows and colour maps (render/window.h): the "C,W" text, the robust default windows on data
// whose percentiles are known by hand, DICOM's linear function at its edges, the hot map's order.
#include "render/window.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace soiq::render {
namespace {

TEST(ParseWindow, ReadsCentreAndWidth) {
  const Result<Window> w = parse_window("40,400");
  ASSERT_TRUE(w.ok()) << w.status().to_string();
  EXPECT_EQ(w->center, 40);
  EXPECT_EQ(w->width, 400);
  const Result<Window> spaced = parse_window(" -600 , 1500.5 ");
  ASSERT_TRUE(spaced.ok()) << spaced.status().to_string();
  EXPECT_EQ(spaced->center, -600);
  EXPECT_EQ(spaced->width, 1500.5);
}

TEST(ParseWindow, RefusesWhatIsNotTwoFiniteNumbersNamingTheText) {
  for (const char* text : {"", "40", "40,", ",400", "a,b", "40;400", "40,400,3", "nan,400", "40,inf", "40,400x"}) {
    const Result<Window> w = parse_window(text);
    ASSERT_FALSE(w.ok()) << text;
    EXPECT_EQ(w.status().code(), StatusCode::kInvalidArgument) << text;
    EXPECT_NE(w.status().message().find("'" + std::string(text) + "'"), std::string::npos) << w.status().message();
    EXPECT_NE(w.status().message().find("CENTRE,WIDTH"), std::string::npos) << w.status().message();
  }
}

TEST(ParseWindow, RefusesAWidthThatIsNotPositive) {
  for (const char* text : {"40,0", "40,-400"}) {
    const Result<Window> w = parse_window(text);
    ASSERT_FALSE(w.ok()) << text;
    EXPECT_EQ(w.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(w.status().message().find("must be > 0"), std::string::npos) << w.status().message();
  }
}

std::vector<float> ramp(int count) {
  std::vector<float> values;
  for (int i = 0; i < count; ++i) values.push_back(static_cast<float>(i));
  return values;
}

TEST(DefaultWindow, SpansTheFirstToTheNinetyNinthPercentile) {
  // 0..100: the 1st percentile is 1 and the 99th 99 (position p * 100 falls on a value).
  std::vector<float> values = ramp(101);
  values.push_back(std::numeric_limits<float>::quiet_NaN());  // ignored, as is an infinity
  values.push_back(std::numeric_limits<float>::infinity());
  const Window w = default_window(values, "CT");
  EXPECT_DOUBLE_EQ(w.center, 50);
  EXPECT_DOUBLE_EQ(w.width, 98);
  // 0..1000 in any order, MR: 10 to 990, interpolation not needed either.
  std::vector<float> shuffled = ramp(1001);
  std::reverse(shuffled.begin(), shuffled.end());
  const Window mr = default_window(shuffled, "MR");
  EXPECT_DOUBLE_EQ(mr.center, 500);
  EXPECT_DOUBLE_EQ(mr.width, 980);
}

TEST(DefaultWindow, InterpolatesBetweenOrderStatistics) {
  // 0..9: the 1st percentile sits at position 0.09 (0.09), the 99th at 8.91 (8.91).
  const Window w = default_window(ramp(10), "CT");
  EXPECT_NEAR(w.center, (0.09 + 8.91) / 2, 1e-9);
  EXPECT_NEAR(w.width, 8.91 - 0.09, 1e-9);
}

TEST(DefaultWindow, PetAndNmRunFromZeroToTheNinetyNinthAndAHalfPercentile) {
  // 0..1000: the 99.5th percentile is 995, and one hot outlier does not move it.
  std::vector<float> values = ramp(1001);
  for (const char* modality : {"PT", "NM"}) {
    const Window w = default_window(values, modality);
    EXPECT_DOUBLE_EQ(w.center, 497.5) << modality;
    EXPECT_DOUBLE_EQ(w.width, 995) << modality;
  }
  values.back() = 1e6f;
  EXPECT_DOUBLE_EQ(default_window(values, "PT").width, 995);
}

TEST(DefaultWindow, AConstantImageGetsAWidthOfOneAroundItsValue) {
  const Window w = default_window(std::vector<float>(50, 7.0f), "CT");
  EXPECT_EQ(w.center, 7);
  EXPECT_EQ(w.width, 1);
  const Window pet = default_window(std::vector<float>(50, 0.0f), "PT");
  EXPECT_EQ(pet.center, 0);
  EXPECT_EQ(pet.width, 1);
  const Window none = default_window({std::numeric_limits<float>::quiet_NaN()}, "CT");
  EXPECT_EQ(none.center, 0);
  EXPECT_EQ(none.width, 1);
  EXPECT_EQ(default_window({}, "MR").width, 1);
}

TEST(WindowLevel, IsBlackAndWhiteAtTheEdgesAndLinearBetween) {
  const Window w{50, 100};  // 0..100
  EXPECT_EQ(window_level(w, -1000), 0);
  EXPECT_EQ(window_level(w, 0), 0);
  EXPECT_EQ(window_level(w, 25), 64);   // 63.75
  EXPECT_EQ(window_level(w, 50), 128);  // 127.5, rounded half away from zero
  EXPECT_EQ(window_level(w, 100), 255);
  EXPECT_EQ(window_level(w, 1e9), 255);
  EXPECT_EQ(window_level(w, std::nan("")), 0);
  // A window narrower than one unit, as PET's SUV windows are.
  EXPECT_EQ(window_level(Window{0.5, 0.5}, 0.5), 128);
}

TEST(ColourMap, PetAndNmAreHotTheRestGray) {
  EXPECT_EQ(colour_map_for_modality("PT"), ColourMap::kHot);
  EXPECT_EQ(colour_map_for_modality("NM"), ColourMap::kHot);
  EXPECT_EQ(colour_map_for_modality("pt"), ColourMap::kHot);
  EXPECT_EQ(colour_map_for_modality("CT"), ColourMap::kGray);
  EXPECT_EQ(colour_map_for_modality("MR"), ColourMap::kGray);
  EXPECT_EQ(colour_map_for_modality(""), ColourMap::kGray);
}

double luminance(const Rgb& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(ColourMap, HotRunsBlackRedYellowWhiteAndBrightensMonotonically) {
  const auto same = [](const Rgb& a, const Rgb& b) { return a.r == b.r && a.g == b.g && a.b == b.b; };
  EXPECT_TRUE(same(colour_of(ColourMap::kHot, 0), Rgb{0, 0, 0}));
  EXPECT_TRUE(same(colour_of(ColourMap::kHot, 85), Rgb{255, 0, 0}));
  EXPECT_TRUE(same(colour_of(ColourMap::kHot, 170), Rgb{255, 255, 0}));
  EXPECT_TRUE(same(colour_of(ColourMap::kHot, 255), Rgb{255, 255, 255}));
  for (int level = 1; level < 256; ++level) {
    EXPECT_GT(luminance(colour_of(ColourMap::kHot, static_cast<uint8_t>(level))),
              luminance(colour_of(ColourMap::kHot, static_cast<uint8_t>(level - 1))))
        << level;
    const Rgb gray = colour_of(ColourMap::kGray, static_cast<uint8_t>(level));
    EXPECT_TRUE(gray.r == level && gray.g == level && gray.b == level) << level;
  }
}

}  // namespace
}  // namespace soiq::render
