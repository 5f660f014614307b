#include "server/http/rendered_params.h"

#include <charconv>
#include <cmath>

#include "core/base/field_rules.h"
#include "render/picture.h"
#include "render/slice_view.h"
#include "render/window.h"
#include "server/http/http_handlers.h"

namespace soiq::server::http {
namespace {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  size_t from = 0;
  while (true) {
    const size_t comma = text.find(',', from);
    parts.push_back(text.substr(from, comma - from));
    if (comma == std::string::npos) return parts;
    from = comma + 1;
  }
}

Result<int64_t> whole(const std::string& name, const std::string& text, int64_t lo, int64_t hi) {
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    return invalid_argument(name + " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
                            ", got '" + text + "'")
        .in_field(name);
  return v;
}

Result<render::PictureSize> viewport_of(const std::string& text) {
  const std::vector<std::string> parts = split_commas(text);
  if (parts.size() == 6)
    return invalid_argument("viewport's source rectangle (sx,sy,sw,sh) is not supported: give viewport=VW,VH")
        .in_field("viewport");
  if (parts.size() != 2) return invalid_argument("viewport must be VW,VH, got '" + text + "'").in_field("viewport");
  SOIQ_ASSIGN_OR_RETURN(const int64_t w, whole("viewport", parts[0], 16, render::kMaxPictureSide));
  SOIQ_ASSIGN_OR_RETURN(const int64_t h, whole("viewport", parts[1], 16, render::kMaxPictureSide));
  return render::PictureSize{int(w), int(h)};
}

Result<render::Window> window_of(const std::string& text) {
  std::vector<std::string> parts = split_commas(text);
  if (parts.size() == 3) {
    if (parts[2] != "linear")
      return invalid_argument("window function '" + parts[2] + "' is not supported: soiqd draws linear windows only")
          .in_field("window");
    parts.pop_back();
  }
  if (parts.size() != 2)
    return invalid_argument("window must be CENTER,WIDTH[,linear], got '" + text + "'").in_field("window");
  Result<render::Window> w = render::parse_window(parts[0] + "," + parts[1]);
  if (!w.ok()) return invalid_argument(w.status().message()).in_field("window");
  return *w;
}

}  // namespace

Result<RenderAsk> rendered_ask(const HttpRequest& req, RenderedParams which,
                               std::optional<render::PictureSize> default_viewport) {
  RenderAsk ask;
  ask.fit = default_viewport;
  const bool soiq = which == RenderedParams::kSoiq;
  std::vector<std::string> seen;
  for (const auto& [name, value] : req.params) {
    for (const std::string& s : seen)
      if (s == name) return invalid_argument(name + " is given twice").in_field(name);
    seen.push_back(name);
    if (name == "window") {
      SOIQ_ASSIGN_OR_RETURN(ask.window, window_of(value));
    } else if (name == "viewport") {
      SOIQ_ASSIGN_OR_RETURN(ask.fit, viewport_of(value));
    } else if (name == "quality") {
      SOIQ_ASSIGN_OR_RETURN(const int64_t q, whole("quality", value, 1, 100));
      ask.picture.jpeg_quality = int(q);
    } else if (soiq && name == "image") {
      SOIQ_RETURN_IF_ERROR(check_text(value, kMaxIdBytes).in_field("image"));
      ask.image = value;
    } else if (soiq && name == "plane") {
      Result<render::Plane> p = render::plane_of_name(value);
      if (!p.ok()) return invalid_argument(p.status().message()).in_field("plane");
      ask.plane = *p;
    } else if (soiq && name == "slice") {
      SOIQ_ASSIGN_OR_RETURN(ask.slice, whole("slice", value, 0, int64_t(1) << 30));
    } else if (soiq && name == "through") {
      if (value != "largest" && value != "centroid")
        return invalid_argument("through must be largest or centroid, got '" + value + "'").in_field("through");
      ask.through = value == "centroid" ? RenderThrough::kCentroid : RenderThrough::kLargest;
    } else if (soiq && name == "montage") {
      if (value != "true" && value != "false")
        return invalid_argument("montage must be true or false, got '" + value + "'").in_field("montage");
      ask.montage = value == "true";
    } else if (soiq && name == "width") {
      SOIQ_ASSIGN_OR_RETURN(const int64_t w, whole("width", value, 16, render::kMaxPictureSide));
      ask.width = int(w);
      ask.fit.reset();
    } else if (soiq && name == "patient-caption") {
      if (value != "true" && value != "false")
        return invalid_argument("patient-caption must be true or false, got '" + value + "'")
            .in_field("patient-caption");
      ask.patient_caption = value == "true";
    } else {
      return invalid_argument("unsupported parameter '" + name + "': this resource takes " +
                              (soiq ? "image, plane, slice, through, montage, width, patient-caption, window, "
                                      "viewport and quality"
                                    : "window, viewport and quality"))
          .in_field(name);
    }
  }
  if (ask.slice && ask.montage)
    return invalid_argument("a montage draws every slice holding the structure: give slice or montage, not both")
        .in_field("slice");
  return ask;
}

std::optional<render::PictureFormat> rendered_format(const HttpRequest& req, bool svg) {
  if (!req.has_header("Accept")) return render::PictureFormat::kJpeg;
  for (const std::string& type : accepted_types(req)) {
    if (type == "image/png") return render::PictureFormat::kPng;
    if (type == "image/jpeg" || type == "image/*" || type == "*/*") return render::PictureFormat::kJpeg;
    if (svg && type == "image/svg+xml") return render::PictureFormat::kSvg;
  }
  return std::nullopt;
}

}  // namespace soiq::server::http
