#pragma once
// The render tests read back what they drew: a PNG decoded by cairo, a JPEG by libjpeg, pixel by
// pixel, so that a test states a colour at a computed position rather than trusting the drawing
// calls. keep_picture() also writes the bytes to $SOIQ_RENDER_PICTURES/NAME when that is set, to
// look at them (`SOIQ_RENDER_PICTURES=/tmp soiq_render_tests`).

#include <cairo.h>
#include <jpeglib.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "render/window.h"

namespace soiq::testing {

struct DecodedPicture {
  int width = 0, height = 0;
  std::vector<render::Rgb> pixels;  // row-major from the top left
  bool ok = false;

  render::Rgb at(int x, int y) const { return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + x]; }
};

inline DecodedPicture decode_png(const std::string& bytes) {
  struct Reader {
    const std::string* bytes;
    size_t offset = 0;
  } reader{&bytes};
  const auto read = [](void* closure, unsigned char* data, unsigned int length) {
    auto* r = static_cast<Reader*>(closure);
    if (r->offset + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
    r->bytes->copy(reinterpret_cast<char*>(data), length, r->offset);
    r->offset += length;
    return CAIRO_STATUS_SUCCESS;
  };
  cairo_surface_t* surface = cairo_image_surface_create_from_png_stream(read, &reader);
  DecodedPicture out;
  if (cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS) {
    out.ok = true;
    out.width = cairo_image_surface_get_width(surface);
    out.height = cairo_image_surface_get_height(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int y = 0; y < out.height; ++y) {
      const auto* row = reinterpret_cast<const uint32_t*>(data + static_cast<size_t>(y) * stride);
      for (int x = 0; x < out.width; ++x) {
        // Every picture soiq draws is opaque, so the premultiplied channels are the colour.
        out.pixels.push_back(
            {static_cast<uint8_t>(row[x] >> 16), static_cast<uint8_t>(row[x] >> 8), static_cast<uint8_t>(row[x])});
      }
    }
  }
  cairo_surface_destroy(surface);
  return out;
}

// libjpeg's default error handler exits the process, which fails the test run loudly enough.
inline DecodedPicture decode_jpeg(const std::string& bytes) {
  jpeg_decompress_struct info{};
  jpeg_error_mgr error{};
  info.err = jpeg_std_error(&error);
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  DecodedPicture out;
  if (jpeg_read_header(&info, TRUE) == JPEG_HEADER_OK) {
    info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&info);
    out.width = static_cast<int>(info.output_width);
    out.height = static_cast<int>(info.output_height);
    std::vector<JSAMPLE> row(static_cast<size_t>(out.width) * 3);
    while (info.output_scanline < info.output_height) {
      JSAMPROW rows[1] = {row.data()};
      jpeg_read_scanlines(&info, rows, 1);
      for (int x = 0; x < out.width; ++x) out.pixels.push_back({row[3 * x], row[3 * x + 1], row[3 * x + 2]});
    }
    jpeg_finish_decompress(&info);
    out.ok = true;
  }
  jpeg_destroy_decompress(&info);
  return out;
}

inline void keep_picture(const std::string& name, const std::string& bytes) {
  const char* folder = std::getenv("SOIQ_RENDER_PICTURES");
  if (folder == nullptr || *folder == '\0') return;
  std::ofstream(std::string(folder) + "/" + name, std::ios::binary) << bytes;
}

}  // namespace soiq::testing
