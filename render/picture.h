#pragma once
// A picture soiq draws (an overlay, a montage, a plot) as the bytes of one file: PNG, SVG or JPEG.
// Drawing goes through cairo (Debian's libcairo2: lines, fills, text with the system's fonts, PNG
// and SVG) and, for JPEG, libjpeg-turbo: soiq encodes no image format and rasterises no font itself.
//
// Inputs   width, height: the picture's size in pixels (SVG: points), each in 1..kMaxPictureSide.
//          draw: called once with a cairo context on that surface, origin top left, y down.
// Output   the file's bytes. JPEG has no alpha: a pixel left translucent comes out as over black.
// Errors   INVALID_ARGUMENT for a size out of range or a JPEG quality outside 1..100; INTERNAL when
//          cairo or libjpeg fails (out of memory).
// Cost     O(width x height). Thread-safe (each call has its own surface).

#include <cairo.h>

#include <functional>
#include <string>

#include "core/base/status.h"

namespace soiq::render {

enum class PictureFormat { kPng, kSvg, kJpeg };

// Every picture is at most this many pixels on a side: a montage of a tall structure or a
// `viewport` asked of WADO-RS is refused before anything is allocated.
inline constexpr int kMaxPictureSide = 8192;

struct PictureOptions {
  PictureFormat format = PictureFormat::kPng;
  int jpeg_quality = 90;  // 1..100, JPEG only
};

// .png, .svg, .jpg, .jpeg (any case). INVALID_ARGUMENT naming the path and the formats otherwise.
Result<PictureFormat> picture_format_of_path(const std::string& path);
// "image/png", "image/svg+xml", "image/jpeg".
const char* media_type(PictureFormat format);

Result<std::string> draw_picture(int width, int height, const PictureOptions& options,
                                 const std::function<void(cairo_t*)>& draw);

}  // namespace soiq::render
