// Pictures as file bytes (render/picture.h): each format decodes back, with libcairo's PNG reader
// and libjpeg, to the size and colours drawn; sizes and qualities out of range are refused.
#include "render/picture.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "tests/render/decoded_picture.h"

namespace soiq::render {
namespace {

// Left half red, right half blue: a picture whose every pixel is known.
void two_halves(cairo_t* cr) {
  cairo_set_source_rgb(cr, 1, 0, 0);
  cairo_rectangle(cr, 0, 0, 16, 24);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 1);
  cairo_rectangle(cr, 16, 0, 16, 24);
  cairo_fill(cr);
}

TEST(DrawPicture, PngDecodesToTheSizeAndColoursDrawn) {
  const Result<std::string> png = draw_picture(32, 24, PictureOptions{}, two_halves);
  ASSERT_TRUE(png.ok()) << png.status().to_string();
  ASSERT_GE(png->size(), 8u);
  EXPECT_EQ(png->substr(1, 3), "PNG");
  const testing::DecodedPicture picture = testing::decode_png(*png);
  ASSERT_TRUE(picture.ok);
  EXPECT_EQ(picture.width, 32);
  EXPECT_EQ(picture.height, 24);
  for (int y = 0; y < 24; ++y) {
    EXPECT_EQ(picture.at(15, y).r, 255);
    EXPECT_EQ(picture.at(15, y).b, 0);
    EXPECT_EQ(picture.at(16, y).r, 0);
    EXPECT_EQ(picture.at(16, y).b, 255);
  }
}

TEST(DrawPicture, JpegStartsWithItsMarkerAndDecodesToTheSizeAndColours) {
  const Result<std::string> jpeg = draw_picture(32, 24, PictureOptions{PictureFormat::kJpeg, 95}, two_halves);
  ASSERT_TRUE(jpeg.ok()) << jpeg.status().to_string();
  ASSERT_GE(jpeg->size(), 4u);
  EXPECT_EQ(static_cast<unsigned char>((*jpeg)[0]), 0xFF);
  EXPECT_EQ(static_cast<unsigned char>((*jpeg)[1]), 0xD8);
  EXPECT_EQ(static_cast<unsigned char>((*jpeg)[jpeg->size() - 2]), 0xFF);
  EXPECT_EQ(static_cast<unsigned char>((*jpeg)[jpeg->size() - 1]), 0xD9);
  const testing::DecodedPicture picture = testing::decode_jpeg(*jpeg);
  ASSERT_TRUE(picture.ok);
  EXPECT_EQ(picture.width, 32);
  EXPECT_EQ(picture.height, 24);
  // Lossy, and chroma is subsampled: a few levels off, away from the edge between the halves.
  const render::Rgb red = picture.at(4, 12), blue = picture.at(28, 12);
  EXPECT_NEAR(red.r, 255, 12);
  EXPECT_NEAR(red.b, 0, 12);
  EXPECT_NEAR(blue.r, 0, 12);
  EXPECT_NEAR(blue.b, 255, 12);
}

TEST(DrawPicture, JpegQualityChangesTheSize) {
  const auto noise = [](cairo_t* cr) {
    for (int n = 0; n < 400; ++n) {
      cairo_set_source_rgb(cr, (n * 37 % 255) / 255.0, (n * 91 % 255) / 255.0, (n * 13 % 255) / 255.0);
      cairo_rectangle(cr, n * 7 % 200, n * 11 % 150, 5, 5);
      cairo_fill(cr);
    }
  };
  const Result<std::string> low = draw_picture(200, 150, PictureOptions{PictureFormat::kJpeg, 10}, noise);
  const Result<std::string> high = draw_picture(200, 150, PictureOptions{PictureFormat::kJpeg, 100}, noise);
  ASSERT_TRUE(low.ok() && high.ok());
  EXPECT_LT(low->size(), high->size());
}

TEST(DrawPicture, SvgIsAnSvgDocumentOfTheSize) {
  const Result<std::string> svg = draw_picture(32, 24, PictureOptions{PictureFormat::kSvg}, two_halves);
  ASSERT_TRUE(svg.ok()) << svg.status().to_string();
  EXPECT_EQ(svg->rfind("<?xml", 0), 0u) << svg->substr(0, 80);
  EXPECT_NE(svg->find("<svg"), std::string::npos);
  EXPECT_NE(svg->find("width=\"32"), std::string::npos) << svg->substr(0, 400);
  EXPECT_NE(svg->find("height=\"24"), std::string::npos);
  EXPECT_NE(svg->find("</svg>"), std::string::npos);
}

TEST(DrawPicture, RefusesSizesOutOfRangeNamingTheLimit) {
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{0, 10}, {10, 0}, {-1, 10}, {kMaxPictureSide + 1, 10}}) {
    const Result<std::string> picture = draw_picture(w, h, PictureOptions{}, two_halves);
    ASSERT_FALSE(picture.ok()) << w << " x " << h;
    EXPECT_EQ(picture.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(picture.status().message().find("1..8192"), std::string::npos) << picture.status().message();
  }
  EXPECT_TRUE(draw_picture(kMaxPictureSide, 1, PictureOptions{}, two_halves).ok());
}

TEST(DrawPicture, RefusesAJpegQualityOutsideOneToAHundred) {
  for (int quality : {0, 101, -5}) {
    const Result<std::string> jpeg = draw_picture(8, 8, PictureOptions{PictureFormat::kJpeg, quality}, two_halves);
    ASSERT_FALSE(jpeg.ok()) << quality;
    EXPECT_EQ(jpeg.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(jpeg.status().message().find("1..100"), std::string::npos) << jpeg.status().message();
  }
  EXPECT_TRUE(draw_picture(8, 8, PictureOptions{PictureFormat::kJpeg, 1}, two_halves).ok());
  // The quality of a PNG is not read.
  EXPECT_TRUE(draw_picture(8, 8, PictureOptions{PictureFormat::kPng, 0}, two_halves).ok());
}

TEST(PictureFormat, FollowsTheFileNameInAnyCase) {
  EXPECT_EQ(*picture_format_of_path("out/a.png"), PictureFormat::kPng);
  EXPECT_EQ(*picture_format_of_path("A.PNG"), PictureFormat::kPng);
  EXPECT_EQ(*picture_format_of_path("x.svg"), PictureFormat::kSvg);
  EXPECT_EQ(*picture_format_of_path("x.jpg"), PictureFormat::kJpeg);
  EXPECT_EQ(*picture_format_of_path("x.JPEG"), PictureFormat::kJpeg);
  for (const char* path : {"x.gif", "png", "x.png.txt", ""}) {
    const Result<PictureFormat> format = picture_format_of_path(path);
    ASSERT_FALSE(format.ok()) << path;
    EXPECT_EQ(format.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(format.status().message().find("'" + std::string(path) + "'"), std::string::npos);
    EXPECT_NE(format.status().message().find(".png, .svg, .jpg or .jpeg"), std::string::npos);
  }
  EXPECT_STREQ(media_type(PictureFormat::kPng), "image/png");
  EXPECT_STREQ(media_type(PictureFormat::kSvg), "image/svg+xml");
  EXPECT_STREQ(media_type(PictureFormat::kJpeg), "image/jpeg");
}

}  // namespace
}  // namespace soiq::render
