#pragma once
// The query parameters of soiqd's pictures over HTTP, read once for WADO-RS rendered and thumbnail
// resources (PS3.18 8.3.5: window, viewport, quality) and soiq's own /soiq/v1/structures/{id}
// pictures (those three and image, plane, slice, through, montage, width), and the picture's media
// type from Accept.
//
// window=C,W[,FUNCTION] (FUNCTION linear only), viewport=VW,VH (the picture fits inside; PS3.18's
// source rectangle sx,sy,sw,sh is not supported), quality=1..100 (JPEG). A parameter the resource
// does not take is INVALID_ARGUMENT naming it and the ones it takes: a viewer asking for an
// annotation learns soiqd draws none, instead of getting a picture without it.
// Media type: PS3.18's default for rendered resources is image/jpeg; Accept chooses image/png
// (or image/svg+xml for soiq's own pictures). Nothing acceptable: NOT_ACCEPTABLE is the caller's 406.

#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "server/app/structure_render.h"
#include "server/http/http_request.h"

namespace soiq::server::http {

// A thumbnail fits this box unless a viewport says otherwise: the size PACS browsers and the query
// page show.
inline constexpr render::PictureSize kThumbnailBox{128, 128};

enum class RenderedParams {
  kWado,  // window, viewport, quality
  kSoiq,  // and image, plane, slice, through, montage, width, patient-caption
};

// The parameters into `ask` (defaults elsewhere as RenderAsk's). `default_viewport`: the box a
// picture fits in when none is asked (thumbnails), nullopt for none.
Result<RenderAsk> rendered_ask(const HttpRequest& req, RenderedParams which,
                               std::optional<render::PictureSize> default_viewport);

// The format Accept asks for, or nullopt when none of ours is acceptable (`svg` allows image/svg+xml).
std::optional<render::PictureFormat> rendered_format(const HttpRequest& req, bool svg);

}  // namespace soiq::server::http
