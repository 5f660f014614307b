#include "render/overlay_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/text_label.h"

namespace soiq::render {

namespace {

struct Layout {
  int columns = 1, rows = 1;
  double px_per_mm = 1;
  double tile_width = 0, tile_height = 0;  // pixels, fractional: tiles tile the picture exactly
  int width = 0, height = 0;
};

std::string size_text(int64_t width, int64_t height) { return std::to_string(width) + " x " + std::to_string(height); }

Result<Layout> layout(int64_t slice_width, int64_t slice_height, double pixel_width_mm, double pixel_height_mm,
                      size_t tiles, int width) {
  if (tiles == 0) return invalid_argument("an overlay needs at least one slice");
  if (slice_width < 1 || slice_height < 1) {
    return invalid_argument("a slice of " + size_text(slice_width, slice_height) + " pixels has nothing to show");
  }
  if (!(pixel_width_mm > 0) || !(pixel_height_mm > 0) || !std::isfinite(pixel_width_mm) ||
      !std::isfinite(pixel_height_mm)) {
    return invalid_argument("a slice's pixel spacing must be finite and > 0");
  }
  if (width < 0 || width > kMaxPictureSide) {
    return invalid_argument("a picture width of " + std::to_string(width) + " px is out of range 0.." +
                            std::to_string(kMaxPictureSide) + " (0: the default)");
  }
  Layout out;
  out.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles))));
  out.rows = static_cast<int>((tiles + static_cast<size_t>(out.columns) - 1) / static_cast<size_t>(out.columns));
  const double width_mm = static_cast<double>(slice_width) * pixel_width_mm;
  const double height_mm = static_cast<double>(slice_height) * pixel_height_mm;
  const double finer_mm = std::min(pixel_width_mm, pixel_height_mm);
  if (width > 0) {
    out.px_per_mm = width / (out.columns * width_mm);
  } else if (tiles == 1) {
    // At least 512 px on the longer side, and a whole number of pixels across the finer voxel side,
    // so that a square-pixel slice has voxels of equal size. The 1e-9 keeps an exact fit exact.
    const double pixels_per_voxel = std::ceil(finer_mm * 512 / std::max(width_mm, height_mm) - 1e-9);
    out.px_per_mm = pixels_per_voxel / finer_mm;
  } else {
    // About 256 px per tile; whole pixels per voxel when that is at least one.
    const double fit = finer_mm * 256 / std::max(width_mm, height_mm);
    out.px_per_mm = (fit >= 1 ? std::round(fit) : fit) / finer_mm;
  }
  out.tile_width = width_mm * out.px_per_mm;
  out.tile_height = height_mm * out.px_per_mm;
  const double picture_width = width > 0 ? width : std::round(out.columns * out.tile_width);
  const double picture_height = std::max(1.0, std::round(out.rows * out.tile_height));
  if (picture_width > kMaxPictureSide || picture_height > kMaxPictureSide) {
    return invalid_argument("a picture of " + size_text(std::llround(picture_width), std::llround(picture_height)) +
                            " px (" + std::to_string(tiles) + " slice" + (tiles == 1 ? "" : "s") + " of " +
                            size_text(slice_width, slice_height) + " pixels) exceeds the largest side of " +
                            std::to_string(kMaxPictureSide) + " px; ask for a smaller width or fewer slices");
  }
  out.width = static_cast<int>(picture_width);
  out.height = static_cast<int>(picture_height);
  return out;
}

Status check_tiles(const std::vector<OverlayScene>& tiles) {
  if (tiles.empty()) return invalid_argument("an overlay needs at least one slice");
  const SliceMask& first = tiles.front().mask;
  for (size_t t = 0; t < tiles.size(); ++t) {
    const OverlayScene& scene = tiles[t];
    const std::string which = "tile " + std::to_string(t);
    if (scene.mask.width != first.width || scene.mask.height != first.height) {
      return invalid_argument(which + " is " + size_text(scene.mask.width, scene.mask.height) +
                              " pixels where tile 0 is " + size_text(first.width, first.height) +
                              "; a montage shows slices of one plane of one grid");
    }
    if (static_cast<int64_t>(scene.mask.inside.size()) != scene.mask.width * scene.mask.height) {
      return invalid_argument(which + "'s mask has " + std::to_string(scene.mask.inside.size()) + " values for " +
                              size_text(scene.mask.width, scene.mask.height) + " pixels");
    }
    if (scene.pixel_width_mm != tiles.front().pixel_width_mm ||
        scene.pixel_height_mm != tiles.front().pixel_height_mm) {
      return invalid_argument(which + "'s pixel spacing differs from tile 0's; a montage shows slices of one grid");
    }
    if (!scene.image) continue;
    if (scene.image->width != scene.mask.width || scene.image->height != scene.mask.height ||
        static_cast<int64_t>(scene.image->values.size()) != scene.image->width * scene.image->height) {
      return invalid_argument(which + "'s image (" + size_text(scene.image->width, scene.image->height) + ", " +
                              std::to_string(scene.image->values.size()) + " values) does not match its mask of " +
                              size_text(scene.mask.width, scene.mask.height) + " pixels");
    }
    if (!(scene.window.width > 0) || !std::isfinite(scene.window.width) || !std::isfinite(scene.window.center)) {
      return invalid_argument(which + "'s window must have a finite centre and a finite width > 0");
    }
  }
  return ok_status();
}

bool inside_at(const SliceMask& mask, int64_t x, int64_t y) {
  return x >= 0 && y >= 0 && x < mask.width && y < mask.height &&
         mask.inside[static_cast<size_t>(y * mask.width + x)] != 0;
}

void set_rgb(cairo_t* cr, const Rgb& c, double alpha) {
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
}

// The slice, opaque, at the tile's own pixels: each pixel takes the voxel under its centre. Scaled
// here rather than by cairo's pattern filter because cairo's SVG surface drops the filter, and a
// browser would then smooth the voxels into each other.
void paint_image(cairo_t* cr, const OverlayScene& scene, double voxel_width, double voxel_height,
                 const Layout& layout) {
  const SliceImage& image = *scene.image;
  std::vector<uint32_t> voxel_colours(image.values.size());
  for (size_t n = 0; n < image.values.size(); ++n) {
    const Rgb c = colour_of(scene.colours, window_level(scene.window, image.values[n]));
    voxel_colours[n] = 0xff000000u | (uint32_t{c.r} << 16) | (uint32_t{c.g} << 8) | c.b;
  }
  const int width = static_cast<int>(std::ceil(layout.tile_width));
  const int height = static_cast<int>(std::ceil(layout.tile_height));
  std::vector<int64_t> column_voxel(static_cast<size_t>(width));
  for (int x = 0; x < width; ++x) {
    column_voxel[static_cast<size_t>(x)] =
        std::min<int64_t>(image.width - 1, static_cast<int64_t>((x + 0.5) / voxel_width));
  }
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  if (cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(surface);
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int y = 0; y < height; ++y) {
      const int64_t row_voxel = std::min<int64_t>(image.height - 1, static_cast<int64_t>((y + 0.5) / voxel_height));
      auto* row = reinterpret_cast<uint32_t*>(data + static_cast<size_t>(y) * static_cast<size_t>(stride));
      for (int x = 0; x < width; ++x) {
        row[x] = voxel_colours[static_cast<size_t>(row_voxel * image.width + column_voxel[static_cast<size_t>(x)])];
      }
    }
    cairo_surface_mark_dirty(surface);
  }
  cairo_set_source_surface(cr, surface, 0, 0);  // an error surface puts cr in error: draw_picture reports it
  // A montage's tiles may start between pixels: nearest keeps each pixel one voxel's grey there too.
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_surface_destroy(surface);
}

// The inside voxels as one path of row runs (one path, so shared edges are not painted twice) and
// the edges between inside and outside as merged straight segments; both in voxel units.
void fill_path(cairo_t* cr, const SliceMask& mask) {
  for (int64_t y = 0; y < mask.height; ++y) {
    for (int64_t x = 0; x < mask.width;) {
      if (!inside_at(mask, x, y)) {
        ++x;
        continue;
      }
      const int64_t begin = x;
      while (inside_at(mask, x, y)) ++x;
      cairo_rectangle(cr, static_cast<double>(begin), static_cast<double>(y), static_cast<double>(x - begin), 1);
    }
  }
}

void outline_path(cairo_t* cr, const SliceMask& mask) {
  // Horizontal edges on line y (between rows y-1 and y), then vertical ones on column x.
  for (int64_t y = 0; y <= mask.height; ++y) {
    for (int64_t x = 0; x < mask.width;) {
      const auto edge = [&](int64_t at) { return inside_at(mask, at, y - 1) != inside_at(mask, at, y); };
      if (!edge(x)) {
        ++x;
        continue;
      }
      const int64_t begin = x;
      while (x < mask.width && edge(x)) ++x;
      cairo_move_to(cr, static_cast<double>(begin), static_cast<double>(y));
      cairo_line_to(cr, static_cast<double>(x), static_cast<double>(y));
    }
  }
  for (int64_t x = 0; x <= mask.width; ++x) {
    for (int64_t y = 0; y < mask.height;) {
      const auto edge = [&](int64_t at) { return inside_at(mask, x - 1, at) != inside_at(mask, x, at); };
      if (!edge(y)) {
        ++y;
        continue;
      }
      const int64_t begin = y;
      while (y < mask.height && edge(y)) ++y;
      cairo_move_to(cr, static_cast<double>(x), static_cast<double>(begin));
      cairo_line_to(cr, static_cast<double>(x), static_cast<double>(y));
    }
  }
}

std::string millimetres(double mm) {
  char text[32];
  std::snprintf(text, sizeof text, "%g mm", mm);
  return text;
}

// Drops the last UTF-8 character of `s` (its continuation bytes, then its lead byte).
void drop_last_character(std::string& s) {
  while (!s.empty()) {
    const unsigned char c = static_cast<unsigned char>(s.back());
    s.pop_back();
    if ((c & 0xC0) != 0x80) return;
  }
}

// Scale bar, letters, label and caption, inside the tile, light on a dark halo.
void draw_annotations(cairo_t* cr, const OverlayScene& scene, const Layout& layout, double tile_width_mm) {
  const double w = layout.tile_width, h = layout.tile_height;
  TextStyle text;
  text.size = std::clamp(std::min(w, h) / 26, 8.0, 18.0);
  text.halo = true;
  TextStyle letter = text;
  letter.bold = true;
  const double margin = text.size * 0.6, line = text.size * 1.25;

  draw_text(cr, scene.label, margin, margin, Anchor::kStart, Anchor::kStart, text);
  draw_text(cr, scene.top, w / 2, margin, Anchor::kCentre, Anchor::kStart, letter);
  draw_text(cr, scene.left, margin, h / 2, Anchor::kStart, Anchor::kCentre, letter);
  draw_text(cr, scene.right, w - margin, h / 2, Anchor::kEnd, Anchor::kCentre, letter);

  // The caption keeps the bottom line, cut with an ellipsis where the tile ends; what it would run
  // into moves up a line.
  const auto fits = [&](const std::string& t) { return margin + text_width(cr, t, text) <= w - margin; };
  std::string caption = scene.caption;
  if (!fits(caption)) {
    const std::string ellipsis = "\u2026";
    while (!caption.empty() && !fits(caption + ellipsis)) drop_last_character(caption);
    caption += ellipsis;
  }
  const double caption_end = margin + text_width(cr, caption, text);
  const double bar_mm = scale_bar_mm(tile_width_mm);
  const double bar_px = bar_mm * layout.px_per_mm;
  const double bar_left = w - margin - bar_px;
  const double letter_half = text_width(cr, scene.bottom, letter) / 2;
  const double letter_bottom = caption_end + margin > w / 2 - letter_half ? h - margin - line : h - margin;
  const double bar_bottom = caption_end + margin > bar_left ? h - margin - line : h - margin;
  draw_text(cr, caption, margin, h - margin, Anchor::kStart, Anchor::kEnd, text);
  draw_text(cr, scene.bottom, w / 2, letter_bottom, Anchor::kCentre, Anchor::kEnd, letter);

  const double thickness = std::max(2.0, std::round(text.size / 5));
  const double halo = std::max(1.0, thickness / 2);
  cairo_rectangle(cr, bar_left - halo, bar_bottom - thickness - halo, bar_px + 2 * halo, thickness + 2 * halo);
  cairo_set_source_rgba(cr, 0, 0, 0, 0.85);
  cairo_fill(cr);
  cairo_rectangle(cr, bar_left, bar_bottom - thickness, bar_px, thickness);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_fill(cr);
  draw_text(cr, millimetres(bar_mm), bar_left + bar_px / 2, bar_bottom - thickness - halo - 2, Anchor::kCentre,
            Anchor::kEnd, text);
}

void draw_tile(cairo_t* cr, const OverlayScene& scene, const Layout& layout) {
  const double voxel_width = scene.pixel_width_mm * layout.px_per_mm;
  const double voxel_height = scene.pixel_height_mm * layout.px_per_mm;
  cairo_rectangle(cr, 0, 0, layout.tile_width, layout.tile_height);
  cairo_clip(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_paint(cr);

  if (scene.image) paint_image(cr, scene, voxel_width, voxel_height, layout);
  cairo_save(cr);
  cairo_scale(cr, voxel_width, voxel_height);
  cairo_new_path(cr);
  fill_path(cr, scene.mask);
  cairo_restore(cr);  // the path stays, in device pixels
  set_rgb(cr, scene.structure_colour, kStructureFillAlpha);
  cairo_fill(cr);

  cairo_save(cr);
  cairo_scale(cr, voxel_width, voxel_height);
  outline_path(cr, scene.mask);
  cairo_restore(cr);
  set_rgb(cr, scene.structure_colour, 1);
  cairo_set_line_width(cr, kOutlineWidthPx);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_SQUARE);  // closes the corners where two segments meet
  cairo_stroke(cr);

  if (scene.annotations)
    draw_annotations(cr, scene, layout, static_cast<double>(scene.mask.width) * scene.pixel_width_mm);
}

}  // namespace

double scale_bar_mm(double tile_width_mm) {
  const double target = tile_width_mm / 5;
  if (!(target > 0) || !std::isfinite(target)) return 1;
  double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (double step : {5.0, 2.0, 1.0}) {
    if (step * decade <= target * (1 + 1e-9)) return step * decade;
  }
  return decade;  // unreachable: decade <= target
}

Result<PictureSize> overlay_size(const SliceAxes& axes, size_t tiles, int width) {
  SOIQ_ASSIGN_OR_RETURN(const Layout l,
                        layout(axes.width, axes.height, axes.pixel_width_mm, axes.pixel_height_mm, tiles, width));
  return PictureSize{l.width, l.height};
}

Result<std::string> overlay_picture(const std::vector<OverlayScene>& tiles, int width, const PictureOptions& options) {
  SOIQ_RETURN_IF_ERROR(check_tiles(tiles));
  const OverlayScene& first = tiles.front();
  SOIQ_ASSIGN_OR_RETURN(const Layout l, layout(first.mask.width, first.mask.height, first.pixel_width_mm,
                                               first.pixel_height_mm, tiles.size(), width));
  return draw_picture(l.width, l.height, options, [&](cairo_t* cr) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_paint(cr);
    for (size_t t = 0; t < tiles.size(); ++t) {
      cairo_save(cr);
      cairo_translate(cr, static_cast<double>(t % l.columns) * l.tile_width,
                      static_cast<double>(t / l.columns) * l.tile_height);
      draw_tile(cr, tiles[t], l);
      cairo_restore(cr);
    }
    // Thin lines between tiles, so that two dark edges do not read as one slice.
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    cairo_set_line_width(cr, 1);
    for (int c = 1; c < l.columns; ++c) {
      cairo_move_to(cr, std::round(c * l.tile_width) + 0.5, 0);
      cairo_line_to(cr, std::round(c * l.tile_width) + 0.5, l.height);
    }
    for (int r = 1; r < l.rows; ++r) {
      cairo_move_to(cr, 0, std::round(r * l.tile_height) + 0.5);
      cairo_line_to(cr, l.width, std::round(r * l.tile_height) + 0.5);
    }
    cairo_stroke(cr);
  });
}

}  // namespace soiq::render
