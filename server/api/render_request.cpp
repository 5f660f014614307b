#include "server/api/render_request.h"

#include <cmath>

#include "core/base/field_rules.h"
#include "server/api/proto_records.h"

namespace soiq::server {

Result<RenderAsk> render_ask(const v1::RenderRequest& request) {
  SOIQ_RETURN_IF_ERROR(check_enum(request.plane(), v1::Plane_IsValid, "plane"));
  SOIQ_RETURN_IF_ERROR(check_enum(request.through(), v1::SliceChoice_IsValid, "through"));
  SOIQ_RETURN_IF_ERROR(check_enum(request.format(), v1::PictureFormat_IsValid, "format"));
  RenderAsk ask;
  if (!request.image().empty()) SOIQ_RETURN_IF_ERROR(check_text(request.image(), kMaxIdBytes).in_field("image"));
  ask.image = request.image();
  switch (request.plane()) {
    case v1::CORONAL:
      ask.plane = render::Plane::kCoronal;
      break;
    case v1::SAGITTAL:
      ask.plane = render::Plane::kSagittal;
      break;
    default:
      ask.plane = render::Plane::kAxial;
      break;
  }
  if (request.has_slice()) ask.slice = request.slice();
  ask.through = request.through() == v1::CENTROID ? RenderThrough::kCentroid : RenderThrough::kLargest;
  ask.montage = request.montage();
  if (request.montage() && request.has_slice())
    return invalid_argument("a montage draws every slice holding the structure: give a slice or a montage, not both")
        .in_field("slice");
  if (request.has_window_center() != request.has_window_width())
    return invalid_argument("give the window's centre and width together, or neither for the default")
        .in_field(request.has_window_center() ? "window_width" : "window_center");
  if (request.has_window_center()) {
    if (!std::isfinite(request.window_center()))
      return invalid_argument("the window's centre must be a finite number").in_field("window_center");
    if (!std::isfinite(request.window_width()) || request.window_width() <= 0)
      return invalid_argument("the window's width must be a finite number > 0").in_field("window_width");
    ask.window = render::Window{request.window_center(), request.window_width()};
  }
  if (request.width() < 0 || request.width() > render::kMaxPictureSide)
    return invalid_argument("width " + std::to_string(request.width()) + " is outside 0.." +
                            std::to_string(render::kMaxPictureSide) + " pixels (0: the default)")
        .in_field("width");
  ask.width = request.width();
  if (request.jpeg_quality() < 0 || request.jpeg_quality() > 100)
    return invalid_argument("JPEG quality " + std::to_string(request.jpeg_quality()) + " is outside 1..100 (0: 90)")
        .in_field("jpeg_quality");
  if (request.jpeg_quality() > 0) ask.picture.jpeg_quality = request.jpeg_quality();
  switch (request.format()) {
    case v1::SVG:
      ask.picture.format = render::PictureFormat::kSvg;
      break;
    case v1::JPEG:
      ask.picture.format = render::PictureFormat::kJpeg;
      break;
    default:
      ask.picture.format = render::PictureFormat::kPng;
      break;
  }
  ask.patient_caption = request.patient_caption();
  return ask;
}

v1::Plane proto_plane(render::Plane plane) {
  switch (plane) {
    case render::Plane::kCoronal:
      return v1::CORONAL;
    case render::Plane::kSagittal:
      return v1::SAGITTAL;
    default:
      return v1::AXIAL;
  }
}

}  // namespace soiq::server
