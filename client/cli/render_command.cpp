#include "client/cli/render_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "render/picture.h"
#include "render/slice_view.h"
#include "render/window.h"

namespace soiq::cli {
namespace {

namespace v1 = soiq::v1;

struct RenderArgs {
  v1::RenderRequest request;
  std::string out;
};

Result<RenderArgs> parse_render_args(int argc, char** argv) {
  RenderArgs a;
  bool have_id = false, have_through = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      SOIQ_ASSIGN_OR_RETURN(a.out, option_value(argc, argv, i));
    } else if (arg == "--image") {
      SOIQ_ASSIGN_OR_RETURN(*a.request.mutable_image(), option_value(argc, argv, i));
    } else if (arg == "--plane") {
      SOIQ_ASSIGN_OR_RETURN(const std::string name, option_value(argc, argv, i));
      Result<render::Plane> plane = render::plane_of_name(name);
      if (!plane.ok()) return invalid_argument("--plane: " + plane.status().message());
      a.request.set_plane(*plane == render::Plane::kCoronal    ? v1::CORONAL
                          : *plane == render::Plane::kSagittal ? v1::SAGITTAL
                                                               : v1::AXIAL);
    } else if (arg == "--slice") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      SOIQ_ASSIGN_OR_RETURN(const int k, parse_int(text, "--slice", 0, 1 << 30));
      a.request.set_slice(k);
    } else if (arg == "--through") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      if (text != "largest" && text != "centroid")
        return invalid_argument("--through must be largest or centroid, got '" + text + "'");
      a.request.set_through(text == "centroid" ? v1::CENTROID : v1::LARGEST);
      have_through = true;
    } else if (arg == "--window") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      Result<render::Window> w = render::parse_window(text);
      if (!w.ok()) return invalid_argument("--window: " + w.status().message());
      a.request.set_window_center(w->center);
      a.request.set_window_width(w->width);
    } else if (arg == "--montage") {
      a.request.set_montage(true);
    } else if (arg == "--width") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      SOIQ_ASSIGN_OR_RETURN(const int width, parse_int(text, "--width", 16, render::kMaxPictureSide));
      a.request.set_width(width);
    } else if (arg == "--quality") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      SOIQ_ASSIGN_OR_RETURN(const int q, parse_int(text, "--quality", 1, 100));
      a.request.set_jpeg_quality(q);
    } else if (arg == "--patient-caption") {
      a.request.set_patient_caption(true);
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (have_id) {
      return invalid_argument("one structure ID, got a second: '" + arg + "'");
    } else {
      SOIQ_ASSIGN_OR_RETURN(const int64_t id, parse_structure_id(arg));
      a.request.set_structure_id(id);
      have_id = true;
    }
  }
  if (!have_id) return invalid_argument("missing structure ID");
  if (a.out.empty()) return invalid_argument("missing -o FILE.png|.svg|.jpg");
  if (a.request.has_slice() && (have_through || a.request.montage()))
    return invalid_argument("--slice names the slice: give it without --through or --montage");
  if (a.request.montage() && have_through)
    return invalid_argument("--montage draws every slice holding the structure: give it without --through");
  Result<render::PictureFormat> format = render::picture_format_of_path(a.out);
  if (!format.ok()) return invalid_argument("-o: " + format.status().message());
  a.request.set_format(*format == render::PictureFormat::kSvg    ? v1::SVG
                       : *format == render::PictureFormat::kJpeg ? v1::JPEG
                                                                 : v1::PNG);
  if (a.request.jpeg_quality() != 0 && *format != render::PictureFormat::kJpeg)
    return invalid_argument("--quality is for JPEG pictures (-o FILE.jpg)");
  return a;
}

const char* plane_word(v1::Plane p) { return p == v1::CORONAL ? "coronal" : p == v1::SAGITTAL ? "sagittal" : "axial"; }

Status render(const RenderArgs& a, const client::ClientOptions& remote) {
  SOIQ_RETURN_IF_ERROR(make_output_folder(a.out));
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  const Result<v1::RenderInfo> drawn = c.render(a.request, a.out);
  if (!drawn.ok() && interrupted()) return interrupted_by_user("no file was written");
  SOIQ_ASSIGN_OR_RETURN(const v1::RenderInfo info, drawn);
  std::string where;
  if (info.slices_size() == 1)
    where = std::string(plane_word(info.plane())) + " slice " + std::to_string(info.slices(0)) + " of 0.." +
            std::to_string(info.slice_count() - 1);
  else
    where = std::string(plane_word(info.plane())) + " montage of " + std::to_string(info.slices_size()) + " slices";
  const std::string image = info.series_uid().empty() ? "the mask alone" : "series " + info.series_uid();
  std::printf("%s over %s, window %.6g,%.6g: %dx%d %s, %lld bytes -> %s\n", where.c_str(), image.c_str(),
              info.window_center(), info.window_width(), info.width(), info.height(), info.media_type().c_str(),
              (long long)info.size_bytes(), a.out.c_str());
  return ok_status();
}

}  // namespace

int run_render_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command("render", parse_render_args(argc, argv), remote,
                          [](const RenderArgs& a, const client::ClientOptions& options) { return render(a, options); });
}

}  // namespace soiq::cli
