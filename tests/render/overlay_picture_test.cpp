// A structure on its image (render/overlay_picture.h), read back pixel by pixel: the grey the
// window gives outside, the fill's tint inside, the outline's colour on the voxel edges, at the
// positions the picture's scale puts them; a one-voxel structure; non-square pixels; montages;
// and the errors.
#include "render/overlay_picture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/render/decoded_picture.h"

namespace soiq::render {
namespace {

// A 10 x 10 slice of 1 mm pixels, all at `value`, with the voxels of `inside` (x, y) in the mask.
OverlayScene scene(const std::vector<std::pair<int, int>>& inside, int64_t width = 10, int64_t height = 10,
                   float value = 100) {
  OverlayScene s;
  s.image = SliceImage{width, height, std::vector<float>(static_cast<size_t>(width * height), value)};
  s.window = Window{100, 200};  // 0..200: the value 100 is grey level 128 (127.5 rounded)
  s.mask = SliceMask{width, height, std::vector<uint8_t>(static_cast<size_t>(width * height), 0)};
  for (const auto& [x, y] : inside) s.mask.inside[static_cast<size_t>(y * width + x)] = 1;
  s.left = "R";
  s.right = "L";
  s.top = "A";
  s.bottom = "P";
  return s;
}

std::vector<std::pair<int, int>> block(int x0, int y0, int x1, int y1) {
  std::vector<std::pair<int, int>> voxels;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) voxels.emplace_back(x, y);
  }
  return voxels;
}

testing::DecodedPicture draw(const std::vector<OverlayScene>& tiles, int width = 0, const std::string& keep = "") {
  const Result<std::string> png = overlay_picture(tiles, width, PictureOptions{});
  EXPECT_TRUE(png.ok()) << png.status().to_string();
  if (!png.ok()) return {};
  if (!keep.empty()) testing::keep_picture(keep, *png);
  return testing::decode_png(*png);
}

// The fill's colour over grey `level`: the structure colour at kStructureFillAlpha.
Rgb tinted(uint8_t level, Rgb over = Rgb{255, 64, 64}) {
  const auto mix = [&](uint8_t c) {
    return static_cast<uint8_t>(std::lround(level * (1 - kStructureFillAlpha) + c * kStructureFillAlpha));
  };
  return {mix(over.r), mix(over.g), mix(over.b)};
}

void expect_colour(const testing::DecodedPicture& p, int x, int y, Rgb want, int tolerance, const std::string& what) {
  const Rgb have = p.at(x, y);
  EXPECT_NEAR(have.r, want.r, tolerance) << what << " at " << x << "," << y;
  EXPECT_NEAR(have.g, want.g, tolerance) << what << " at " << x << "," << y;
  EXPECT_NEAR(have.b, want.b, tolerance) << what << " at " << x << "," << y;
}

constexpr Rgb kRed{255, 64, 64}, kGrey128{128, 128, 128};
// Cairo composites in 8 bits, with its own rounding: one level either way.
constexpr int kBlend = 2;

TEST(OverlayPicture, GreyOutsideTintInsideOutlineOnTheVoxelEdges) {
  // 10 x 10 mm: 512 px at least on the longer side, in whole pixels per voxel: 52 px, 520 x 520.
  const testing::DecodedPicture p = draw({scene(block(3, 2, 7, 5))}, 0, "overlay_block.png");
  ASSERT_TRUE(p.ok);
  ASSERT_EQ(p.width, 520);
  ASSERT_EQ(p.height, 520);
  const int v = 52;  // pixels per voxel
  // Outside, away from the text: voxels (8, 1), (1, 7), (8, 7) as the window makes them.
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{8, 1}, {1, 7}, {8, 7}, {5, 7}}) {
    expect_colour(p, x * v + v / 2, y * v + v / 2, kGrey128, 0, "outside");
  }
  // Inside: every voxel's centre is tinted.
  for (const auto& [x, y] : block(3, 2, 7, 5))
    expect_colour(p, x * v + v / 2, y * v + v / 2, tinted(128), kBlend, "inside");
  // The outline: 2 px centred on the edges x = 3 and 7, y = 2 and 5 (voxel units), so the pixel on
  // each side of an edge is covered whole; one further out is grey, one further in tinted.
  const int mid_y = 3 * v + v / 2, mid_x = 5 * v;
  for (int x : {3 * v - 1, 3 * v, 7 * v - 1, 7 * v}) expect_colour(p, x, mid_y, kRed, 1, "vertical edge");
  for (int y : {2 * v - 1, 2 * v, 5 * v - 1, 5 * v}) expect_colour(p, mid_x, y, kRed, 1, "horizontal edge");
  expect_colour(p, 3 * v - 2, mid_y, kGrey128, 0, "left of the left edge");
  expect_colour(p, 3 * v + 1, mid_y, tinted(128), kBlend, "right of the left edge");
  expect_colour(p, mid_x, 5 * v + 1, kGrey128, 0, "below the bottom edge");
  // The corners are closed (square caps).
  expect_colour(p, 3 * v - 1, 2 * v - 1, kRed, 1, "top-left corner");
  expect_colour(p, 7 * v, 5 * v, kRed, 1, "bottom-right corner");
}

TEST(OverlayPicture, AOneVoxelStructureIsAVisibleSquare) {
  const testing::DecodedPicture p = draw({scene({{5, 4}})});
  ASSERT_TRUE(p.ok);
  const int v = 52;
  expect_colour(p, 5 * v + v / 2, 4 * v + v / 2, tinted(128), kBlend, "its centre");
  expect_colour(p, 5 * v, 4 * v + v / 2, kRed, 1, "left edge");
  expect_colour(p, 6 * v - 1, 4 * v + v / 2, kRed, 1, "right edge");
  expect_colour(p, 5 * v + v / 2, 4 * v, kRed, 1, "top edge");
  expect_colour(p, 5 * v + v / 2, 5 * v - 1, kRed, 1, "bottom edge");
  expect_colour(p, 4 * v + v / 2, 4 * v + v / 2, kGrey128, 0, "the voxel to its left");
}

TEST(OverlayPicture, AOneVoxelStructureStaysVisibleWhenVoxelsAreSmallerThanAPixel) {
  // 400 x 400 voxels in 200 px: half a pixel per voxel, and still a mark of the outline's colour.
  OverlayScene s = scene({{201, 201}}, 400, 400);
  const testing::DecodedPicture p = draw({s}, 200);
  ASSERT_TRUE(p.ok);
  ASSERT_EQ(p.width, 200);
  expect_colour(p, 100, 100, kRed, 1, "the voxel");
}

TEST(OverlayPicture, NonSquarePixelsKeepTheirAspect) {
  // 10 x 4 pixels of 0.7 x 3 mm: 7 mm wide, 12 mm tall. At 700 px wide, 100 px per mm: a voxel is
  // 70 px wide and 300 px tall.
  OverlayScene s = scene({{2, 1}}, 10, 4);
  s.pixel_width_mm = 0.7;
  s.pixel_height_mm = 3;
  const testing::DecodedPicture p = draw({s}, 700, "overlay_aspect.png");
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.width, 700);
  EXPECT_EQ(p.height, 1200);
  expect_colour(p, 175, 450, tinted(128), kBlend, "inside");
  expect_colour(p, 140, 450, kRed, 1, "left edge");
  expect_colour(p, 209, 450, kRed, 1, "right edge");
  expect_colour(p, 175, 300, kRed, 1, "top edge");
  expect_colour(p, 175, 599, kRed, 1, "bottom edge");
  expect_colour(p, 175, 295, kGrey128, 0, "above");
  expect_colour(p, 175, 605, kGrey128, 0, "below");
  // The default size: the finer side (0.7 mm) in whole pixels, the taller side at least 512 px.
  const testing::DecodedPicture d = draw({s});
  ASSERT_TRUE(d.ok);
  EXPECT_EQ(d.width, 300);   // 30 px per 0.7 mm voxel
  EXPECT_EQ(d.height, 514);  // 12 mm at 30 / 0.7 px per mm, 514.3 rounded
}

TEST(OverlayPicture, WithoutAnImageTheMaskIsDrawnOnBlack) {
  OverlayScene s = scene(block(3, 3, 6, 6));
  s.image.reset();
  const testing::DecodedPicture p = draw({s});
  ASSERT_TRUE(p.ok);
  expect_colour(p, 8 * 52 + 26, 26 + 52, Rgb{0, 0, 0}, 0, "outside");
  expect_colour(p, 4 * 52 + 26, 4 * 52 + 26, tinted(0), kBlend, "inside");
}

TEST(OverlayPicture, PetUsesTheHotMapThroughTheWindow) {
  OverlayScene s = scene({}, 10, 10, 50);  // 50 in 0..200: level 64
  s.colours = ColourMap::kHot;
  const testing::DecodedPicture p = draw({s});
  ASSERT_TRUE(p.ok);
  expect_colour(p, 442, 78, colour_of(ColourMap::kHot, 64), 0, "a hot voxel");
}

TEST(OverlayPicture, TheCaptionIsDrawnBottomLeftLightOnDark) {
  // White text pixels at the bottom left with a caption, none without.
  const auto white_pixels = [](const testing::DecodedPicture& p) {
    int count = 0;
    for (int y = p.height - 40; y < p.height; ++y) {
      for (int x = 0; x < 200; ++x) count += p.at(x, y).r > 240 && p.at(x, y).g > 240 && p.at(x, y).b > 240;
    }
    return count;
  };
  OverlayScene s = scene(block(3, 3, 6, 6));
  EXPECT_EQ(white_pixels(draw({s})), 0);
  s.caption = "hippocampus_L  CT 2019-03-04";
  s.label = "k 42";
  EXPECT_GT(white_pixels(draw({s}, 0, "overlay_caption.png")), 50);
}

TEST(OverlayPicture, AMontageLaysTilesOutInRowsOfCeilSqrt) {
  std::vector<OverlayScene> tiles;
  for (int t = 0; t < 5; ++t) {
    tiles.push_back(scene(block(2, 2, 4 + t, 5)));
    tiles.back().label = "k " + std::to_string(10 + t);
  }
  // 5 tiles: 3 columns, 2 rows; 256 px per tile is 25.6 px per voxel, 26 whole: 260 px tiles.
  const SliceAxes axes{Plane::kAxial, 2, 0, 1, false, false, 5, 10, 10, 1, 1, "R", "L", "A", "P"};
  const Result<PictureSize> size = overlay_size(axes, 5, 0);
  ASSERT_TRUE(size.ok()) << size.status().to_string();
  EXPECT_EQ(size->width, 780);
  EXPECT_EQ(size->height, 520);
  const testing::DecodedPicture p = draw(tiles, 0, "overlay_montage.png");
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.width, 780);
  EXPECT_EQ(p.height, 520);
  // Tile 4 (column 1, row 1) holds voxel (7, 3); tile 0 does not. The sixth cell is black.
  expect_colour(p, 260 + 7 * 26 + 13, 260 + 3 * 26 + 13, tinted(128), kBlend, "tile 4");
  expect_colour(p, 7 * 26 + 13, 3 * 26 + 13, kGrey128, 0, "tile 0");
  expect_colour(p, 520 + 130, 260 + 130, Rgb{0, 0, 0}, 0, "the empty cell");
  // At a given width the tiles share it: 3 x 100 px.
  EXPECT_EQ(overlay_size(axes, 5, 300)->height, 200);
}

// A CT-like slice through the whole path a server takes: a volume, its axes, the slices, the scene.
TEST(OverlayPicture, ACtSliceThroughSliceAxesShowsAirBlackBoneWhiteAndTheStructureTinted) {
  ImageGeometry g;
  g.dims = {160, 128, 3};
  g.spacing_mm = {0.8, 0.8, 3};
  Image ct{g, std::vector<float>(static_cast<size_t>(g.voxel_count()))};
  Mask tumour{g, std::vector<uint8_t>(static_cast<size_t>(g.voxel_count()), 0)};
  const auto in_ellipse = [](double x, double y, double cx, double cy, double rx, double ry) {
    return (x - cx) * (x - cx) / (rx * rx) + (y - cy) * (y - cy) / (ry * ry) <= 1;
  };
  for (int64_t k = 0; k < 3; ++k) {
    for (int64_t j = 0; j < 128; ++j) {
      for (int64_t i = 0; i < 160; ++i) {
        const size_t n = static_cast<size_t>(i + 160 * (j + 128 * k));
        float hu = -1000;                                                                      // air
        if (in_ellipse(i, j, 80, 64, 70, 50)) hu = 40 + (i * 7 + j * 13) % 21 - 10;            // soft tissue
        if (in_ellipse(i, j, 52, 58, 20, 30) || in_ellipse(i, j, 108, 58, 20, 30)) hu = -850;  // lungs
        if (in_ellipse(i, j, 80, 100, 9, 9)) hu = 700;                                         // a vertebra
        const bool lesion = k == 1 && in_ellipse(i, j, 108, 50, 7, 7);  // in the patient's left lung
        if (lesion) hu = 30;
        ct.voxels[n] = hu;
        tumour.voxels[n] = lesion;
      }
    }
  }
  const SliceAxes axes = *slice_axes(g, Plane::kAxial);
  const std::vector<int64_t> per_slice = inside_per_slice(from_mask(tumour), axes);
  const int64_t largest = std::max_element(per_slice.begin(), per_slice.end()) - per_slice.begin();
  ASSERT_EQ(largest, 1);
  OverlayScene s;
  s.image = *image_slice(ct, axes, largest);
  s.mask = *mask_slice(from_mask(tumour), axes, largest);
  s.window = Window{40, 400};
  s.pixel_width_mm = axes.pixel_width_mm;
  s.pixel_height_mm = axes.pixel_height_mm;
  s.left = axes.left;
  s.right = axes.right;
  s.top = axes.top;
  s.bottom = axes.bottom;
  s.label = "k " + std::to_string(largest);
  s.caption = "lesion_L  CT  W 400 C 40";
  const testing::DecodedPicture p = draw({s}, 0, "overlay_ct.png");
  ASSERT_TRUE(p.ok);
  // 128 mm across the 160 voxels: 4 px per voxel reaches 512 (3.2 would not be whole), 640 x 512.
  ASSERT_EQ(p.width, 640);
  ASSERT_EQ(p.height, 512);
  const auto centre = [](int i, int j) { return std::pair<int, int>(i * 4 + 2, j * 4 + 2); };
  const auto [air_x, air_y] = centre(5, 30);
  expect_colour(p, air_x, air_y, Rgb{0, 0, 0}, 0, "air");
  const auto [bone_x, bone_y] = centre(80, 100);
  expect_colour(p, bone_x, bone_y, Rgb{255, 255, 255}, 0, "bone");
  const auto [lesion_x, lesion_y] = centre(108, 50);
  expect_colour(p, lesion_x, lesion_y, tinted(window_level(s.window, 30)), kBlend, "the lesion");
  // The lesion is in the patient's left: on the screen's right half, with "L" at the right edge.
  EXPECT_EQ(s.right, "L");
  EXPECT_GT(lesion_x, p.width / 2);
}

TEST(ScaleBar, IsTheLargestRoundLengthWithinAFifthOfTheWidth) {
  EXPECT_DOUBLE_EQ(scale_bar_mm(10), 2);
  EXPECT_DOUBLE_EQ(scale_bar_mm(512), 100);
  EXPECT_DOUBLE_EQ(scale_bar_mm(358.4), 50);
  EXPECT_DOUBLE_EQ(scale_bar_mm(250), 50);
  EXPECT_DOUBLE_EQ(scale_bar_mm(7), 1);
  EXPECT_DOUBLE_EQ(scale_bar_mm(3), 0.5);
}

TEST(OverlayPicture, SvgAndJpegToo) {
  const OverlayScene s = scene(block(3, 3, 6, 6));
  const Result<std::string> svg = overlay_picture({s}, 0, PictureOptions{PictureFormat::kSvg});
  ASSERT_TRUE(svg.ok()) << svg.status().to_string();
  EXPECT_EQ(svg->rfind("<?xml", 0), 0u);
  EXPECT_NE(svg->find("<svg"), std::string::npos);
  EXPECT_NE(svg->find("width=\"520"), std::string::npos);
  // The slice goes in at the picture's own pixels, so a browser has nothing to smooth.
  EXPECT_NE(svg->find("<image id=\"image"), std::string::npos);
  EXPECT_NE(svg->find("width=\"520\" height=\"520\" xlink:href=\"data:image/png"), std::string::npos);
  const Result<std::string> jpeg = overlay_picture({s}, 0, PictureOptions{PictureFormat::kJpeg, 90});
  ASSERT_TRUE(jpeg.ok()) << jpeg.status().to_string();
  const testing::DecodedPicture p = testing::decode_jpeg(*jpeg);
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.width, 520);
  EXPECT_EQ(p.height, 520);
}

void expect_overlay_refused(const Result<std::string>& r, const std::string& phrase) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find(phrase), std::string::npos) << r.status().message();
}

TEST(OverlayPicture, RefusesTilesThatDoNotFitTogether) {
  expect_overlay_refused(overlay_picture({}, 0, PictureOptions{}), "at least one slice");
  expect_overlay_refused(overlay_picture({scene({}), scene({}, 10, 12)}, 0, PictureOptions{}),
                         "tile 1 is 10 x 12 pixels where tile 0 is 10 x 10");
  OverlayScene wrong_image = scene({});
  wrong_image.image->width = 9;
  expect_overlay_refused(overlay_picture({wrong_image}, 0, PictureOptions{}), "does not match its mask");
  OverlayScene no_width = scene({});
  no_width.window.width = 0;
  expect_overlay_refused(overlay_picture({no_width}, 0, PictureOptions{}), "width > 0");
  OverlayScene flat = scene({});
  flat.pixel_height_mm = 0;
  expect_overlay_refused(overlay_picture({flat}, 0, PictureOptions{}), "spacing");
}

TEST(OverlaySize, RefusesAPictureOverTheLargestSideNamingItsSize) {
  // 10 x 100 pixels of 1 mm at 8000 px wide would be 80000 px tall.
  const SliceAxes tall{Plane::kSagittal, 0, 1, 2, false, true, 1, 10, 100, 1, 1, "A", "P", "S", "I"};
  const Result<PictureSize> size = overlay_size(tall, 1, 8000);
  ASSERT_FALSE(size.ok());
  EXPECT_EQ(size.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(size.status().message().find("8000 x 80000"), std::string::npos) << size.status().message();
  EXPECT_NE(size.status().message().find("8192"), std::string::npos);
  EXPECT_EQ(overlay_size(tall, 1, kMaxPictureSide + 1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(overlay_size(tall, 0, 0).status().code(), StatusCode::kInvalidArgument);
  // A montage of 100 tiles of 10 x 100: 10 x 10 tiles of about 26 x 256 px, fine.
  EXPECT_TRUE(overlay_size(tall, 100, 0).ok());
}

}  // namespace
}  // namespace soiq::render
