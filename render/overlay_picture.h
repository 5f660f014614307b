#pragma once
// A structure on its image: the windowed slice, the structure's voxels as a translucent fill with
// an opaque outline along the pixel edges between inside and outside (so a one-voxel structure is
// a visible square, and what is drawn is exactly the voxel set soiq computed), a scale bar with a
// round length (1, 2 or 5 x 10^n mm, about a fifth of the width), the orientation letters at the
// four edges, and a caption. Pixels are drawn as squares scaled by their spacing (a 0.7 x 3 mm
// pixel is 3/0.7 times as tall as wide), never smoothed. Without an image (a mesh uploaded alone)
// the mask is drawn on black.
//
// A montage lays tiles out in rows (columns = ceil(sqrt(tiles))), each with its slice number.
//
// Inputs   tiles: 1 or more scenes, all slices of one grid and plane (same pixel size). width: of
//          the whole picture in pixels; 0 picks one: 512 px for a single tile's longer side at
//          least (a slice is scaled up, whole pixels per voxel when they fit), 256 px per tile of a
//          montage. The height follows from the tiles' aspect.
// Errors   INVALID_ARGUMENT for no tiles, tiles of different sizes, an image and mask of different
//          sizes, or a picture whose side would exceed kMaxPictureSide (naming the size); those of
//          draw_picture.

#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "render/picture.h"
#include "render/slice_view.h"
#include "render/window.h"

namespace soiq::render {

struct OverlayScene {
  std::optional<SliceImage> image;  // nullopt: the mask alone
  Window window;
  ColourMap colours = ColourMap::kGray;
  SliceMask mask;
  double pixel_width_mm = 1, pixel_height_mm = 1;
  std::string left, right, top, bottom;  // orientation letters
  std::string caption;                   // bottom left; "" none
  std::string label;                     // top left, e.g. "k 42"; "" none
  // Letters, scale bar, label and caption; off for thumbnails, where at 128 pixels they would
  // cover what the thumbnail is for.
  bool annotations = true;
  Rgb structure_colour{255, 64, 64};
};

Result<std::string> overlay_picture(const std::vector<OverlayScene>& tiles, int width, const PictureOptions& options);

// The montage's size in pixels for `tiles` tiles of `axes`' slices at `width` (0: the default
// above): what overlay_picture will draw, for checking a request against kMaxPictureSide first.
struct PictureSize {
  int width = 0, height = 0;
};
Result<PictureSize> overlay_size(const SliceAxes& axes, size_t tiles, int width);

// How the structure is drawn, for a reader checking pixels: its fill is structure_colour at this
// opacity over the image, its outline structure_colour, opaque, this many pixels wide, centred on
// the voxel edges.
inline constexpr double kStructureFillAlpha = 0.35;
inline constexpr double kOutlineWidthPx = 2;

// The scale bar's length for a tile `tile_width_mm` wide: the largest 1, 2 or 5 x 10^n mm at most a
// fifth of it.
double scale_bar_mm(double tile_width_mm);

}  // namespace soiq::render
