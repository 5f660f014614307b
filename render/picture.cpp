#include "render/picture.h"

#include <cairo-svg.h>
#include <jpeglib.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <memory>
#include <vector>

namespace soiq::render {

namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

Status cairo_failure(cairo_status_t status, const char* what) {
  return internal_error(std::string("cairo could not ") + what + ": " + cairo_status_to_string(status));
}

// Runs `draw` on `surface` and reports the first error cairo recorded (cairo's calls after an
// error do nothing, so one check at the end sees it).
Status draw_on(cairo_surface_t* surface, const std::function<void(cairo_t*)>& draw) {
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    return cairo_failure(cairo_surface_status(surface), "make a surface");
  }
  cairo_t* cr = cairo_create(surface);
  draw(cr);
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  if (status != CAIRO_STATUS_SUCCESS) return cairo_failure(status, "draw");
  cairo_surface_flush(surface);
  return ok_status();
}

// libjpeg reports errors through error_exit, which must not return; the default one calls exit().
// This one jumps back to encode_jpeg with the message.
struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void jpeg_error_exit(j_common_ptr info) {
  auto* error = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, error->message);
  std::longjmp(error->jump, 1);
}

// A destination that appends to a string, so the bytes need no second copy or free().
struct JpegDestination {
  jpeg_destination_mgr manager;
  std::string* out;
  std::vector<JOCTET> buffer;
};

void jpeg_init_destination(j_compress_ptr info) {
  auto* dest = reinterpret_cast<JpegDestination*>(info->dest);
  dest->manager.next_output_byte = dest->buffer.data();
  dest->manager.free_in_buffer = dest->buffer.size();
}

boolean jpeg_empty_output_buffer(j_compress_ptr info) {
  auto* dest = reinterpret_cast<JpegDestination*>(info->dest);
  dest->out->append(reinterpret_cast<const char*>(dest->buffer.data()), dest->buffer.size());
  jpeg_init_destination(info);
  return TRUE;
}

void jpeg_term_destination(j_compress_ptr info) {
  auto* dest = reinterpret_cast<JpegDestination*>(info->dest);
  dest->out->append(reinterpret_cast<const char*>(dest->buffer.data()),
                    dest->buffer.size() - dest->manager.free_in_buffer);
}

// The RGB of cairo's premultiplied ARGB32 pixels: JPEG has no alpha, so a translucent pixel
// comes out as it would over black.
void argb_row_to_rgb(const unsigned char* argb, int width, JSAMPLE* rgb) {
  const auto* pixels = reinterpret_cast<const uint32_t*>(argb);
  for (int x = 0; x < width; ++x) {
    rgb[3 * x] = static_cast<JSAMPLE>((pixels[x] >> 16) & 0xff);
    rgb[3 * x + 1] = static_cast<JSAMPLE>((pixels[x] >> 8) & 0xff);
    rgb[3 * x + 2] = static_cast<JSAMPLE>(pixels[x] & 0xff);
  }
}

// Every C++ object lives in the caller's frame or before setjmp, so the longjmp out of libjpeg
// skips no destructor.
Status encode_jpeg(cairo_surface_t* surface, int quality, std::string& out) {
  const int width = cairo_image_surface_get_width(surface), height = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  std::vector<JSAMPLE> row(static_cast<size_t>(width) * 3);
  JpegDestination destination{{}, &out, std::vector<JOCTET>(64 * 1024)};
  JpegError error{};
  jpeg_compress_struct info{};
  info.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = jpeg_error_exit;
  if (setjmp(error.jump) != 0) {
    jpeg_destroy_compress(&info);
    return internal_error(std::string("libjpeg could not encode the picture: ") + error.message);
  }
  jpeg_create_compress(&info);
  destination.manager.init_destination = jpeg_init_destination;
  destination.manager.empty_output_buffer = jpeg_empty_output_buffer;
  destination.manager.term_destination = jpeg_term_destination;
  info.dest = &destination.manager;
  info.image_width = static_cast<JDIMENSION>(width);
  info.image_height = static_cast<JDIMENSION>(height);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    argb_row_to_rgb(data + static_cast<size_t>(info.next_scanline) * static_cast<size_t>(stride), width, row.data());
    JSAMPROW rows[1] = {row.data()};
    jpeg_write_scanlines(&info, rows, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  return ok_status();
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

Result<PictureFormat> picture_format_of_path(const std::string& path) {
  const std::string name = lower(path);
  if (ends_with(name, ".png")) return PictureFormat::kPng;
  if (ends_with(name, ".svg")) return PictureFormat::kSvg;
  if (ends_with(name, ".jpg") || ends_with(name, ".jpeg")) return PictureFormat::kJpeg;
  return invalid_argument("'" + path + "' does not name a picture format; end it in .png, .svg, .jpg or .jpeg");
}

const char* media_type(PictureFormat format) {
  switch (format) {
    case PictureFormat::kPng:
      return "image/png";
    case PictureFormat::kSvg:
      return "image/svg+xml";
    case PictureFormat::kJpeg:
      break;
  }
  return "image/jpeg";
}

Result<std::string> draw_picture(int width, int height, const PictureOptions& options,
                                 const std::function<void(cairo_t*)>& draw) {
  if (width < 1 || height < 1 || width > kMaxPictureSide || height > kMaxPictureSide) {
    return invalid_argument("a picture of " + std::to_string(width) + " x " + std::to_string(height) +
                            " px is out of range; each side must be 1.." + std::to_string(kMaxPictureSide) + " px");
  }
  if (options.format == PictureFormat::kJpeg && (options.jpeg_quality < 1 || options.jpeg_quality > 100)) {
    return invalid_argument("JPEG quality " + std::to_string(options.jpeg_quality) + " is out of range 1..100");
  }
  std::string out;
  if (options.format == PictureFormat::kSvg) {
    SurfacePtr surface(cairo_svg_surface_create_for_stream(append_to_string, &out, width, height),
                       cairo_surface_destroy);
    SOIQ_RETURN_IF_ERROR(draw_on(surface.get(), draw));
    cairo_surface_finish(surface.get());  // writes the document's end
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
      return cairo_failure(cairo_surface_status(surface.get()), "write SVG");
    }
    return out;
  }
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height), cairo_surface_destroy);
  SOIQ_RETURN_IF_ERROR(draw_on(surface.get(), draw));
  if (options.format == PictureFormat::kJpeg) {
    SOIQ_RETURN_IF_ERROR(encode_jpeg(surface.get(), options.jpeg_quality, out));
    return out;
  }
  if (const cairo_status_t status = cairo_surface_write_to_png_stream(surface.get(), append_to_string, &out);
      status != CAIRO_STATUS_SUCCESS) {
    return cairo_failure(status, "write PNG");
  }
  return out;
}

}  // namespace soiq::render
