#pragma once
// The Render RPC's request as the app's RenderAsk (server/app/structure_render.h), checked: enums
// known, width within 0..render::kMaxPictureSide, JPEG quality within 0..100, the window's centre
// and width both given or neither, its width finite and > 0, the image reference valid text.
// Errors: INVALID_ARGUMENT with the field's path (Status::in_field).

#include "core/base/status.h"
#include "server/app/structure_render.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

Result<RenderAsk> render_ask(const v1::RenderRequest& request);

v1::Plane proto_plane(render::Plane plane);

}  // namespace soiq::server
