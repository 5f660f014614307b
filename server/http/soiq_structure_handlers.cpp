// /soiq/v1/structures/{id}/...: one structure as a picture or a file, for the query page's rows and
// any HTTP client: `rendered` (soiq render's options as parameters), `thumbnail` (the same, fitted
// to a viewport, 128x128 unless asked), `seg` (its DICOM SEG, as WADO-RS serves it), `mask` (its
// voxels on the grid of its image as gzipped NIfTI, else on the 1 mm grid around it) and `surface`
// (the stored surface as binary STL). Downloads say their file name in Content-Disposition.
#include "server/app/grid_choice.h"
#include "server/app/stored_surface_bytes.h"
#include "server/app/structure_conversion.h"
#include "server/app/structure_object_uids.h"
#include "server/app/structure_render.h"
#include "server/app/structure_seg.h"
#include "server/http/http_handlers.h"
#include "server/http/rendered_params.h"

namespace soiq::server::http {
namespace {

Result<int64_t> structure_id(const std::string& text) {
  int64_t id = 0;
  for (const char ch : text) {
    if (ch < '0' || ch > '9' || id > (int64_t(1) << 50)) return not_found("structure '" + text + "' not found");
    id = id * 10 + (ch - '0');
  }
  if (text.empty() || id <= 0) return not_found("structure '" + text + "' not found");
  return id;
}

HttpReply download(std::string bytes, const std::string& content_type, const std::string& file_name) {
  HttpReply r;
  r.content_type = content_type;
  r.body = std::move(bytes);
  r.headers.emplace("Content-Disposition", "attachment; filename=\"" + file_name + "\"");
  return r;
}

Result<HttpReply> picture(const HandlerContext& c, int64_t id, bool thumbnail, const HttpRequest& req) {
  const std::optional<render::PictureFormat> format = rendered_format(req, true);
  if (!format) return HttpReply{406, "image/jpeg, image/png or image/svg+xml", "", {}};
  SOIQ_ASSIGN_OR_RETURN(
      RenderAsk ask, rendered_ask(req, RenderedParams::kSoiq, thumbnail ? std::optional(kThumbnailBox) : std::nullopt));
  ask.picture.format = *format;
  ask.thumbnail = thumbnail;
  const AppEngines& e = c.engines;
  SOIQ_ASSIGN_OR_RETURN(RenderedPicture p,
                        render_structure(e.store, e.features, e.pool, id, ask, stop_when_client_gone(req)));
  HttpReply r;
  r.content_type = render::media_type(p.format);
  r.body = std::move(p.bytes);
  r.headers.emplace("Cache-Control", "private, max-age=60");
  return r;
}

Result<HttpReply> seg(const HandlerContext& c, int64_t id, const HttpRequest& req) {
  const AppEngines& e = c.engines;
  SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord s, e.store.get_structure(id));
  const StructureObjectUids uids = structure_object_uids(s, db::StructureObject::kSeg);
  std::optional<BudgetedSeg> written;
  auto work = [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(BudgetedSeg w,
                          structure_seg(e.store, e.features, e.budget, {id}, seg_series_description(s.name), &uids,
                                        stop_when_client_gone(req)));
    written.emplace(std::move(w));
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(e.pool.call(work));
  HttpReply r =
      download(std::move(written->seg.bytes), "application/dicom", "structure-" + std::to_string(id) + "-seg.dcm");
  r.held.push_back(std::move(written->held));
  return r;
}

Result<HttpReply> mask(const HandlerContext& c, int64_t id, const HttpRequest& req) {
  const AppEngines& e = c.engines;
  SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord s, e.store.get_structure(id));
  GridChoice choice;  // 1 mm around the structure, unless it has the image it was drawn on
  if (!s.source_series_uid.empty() && e.store.get_series(s.source_series_uid).ok()) {
    choice.kind = GridChoice::Kind::kSeriesUid;
    choice.series = s.source_series_uid;
  }
  SOIQ_ASSIGN_OR_RETURN(
      StructureConversion conversion,
      convert_structure(e.store, e.features, e.pool, id, choice, FillRule::kNonZero, true, stop_when_client_gone(req)));
  SOIQ_ASSIGN_OR_RETURN(std::string bytes, mask_nifti_bytes(conversion.voxelization.volume, e.config.max_grid_voxels));
  return download(std::move(bytes), "application/gzip", "structure-" + std::to_string(id) + "-mask.nii.gz");
}

Result<HttpReply> surface(const HandlerContext& c, int64_t id) {
  SOIQ_ASSIGN_OR_RETURN(std::string bytes, stored_surface_bytes(c.engines.store, c.engines.features, id, "stl", false));
  return download(std::move(bytes), "model/stl", "structure-" + std::to_string(id) + ".stl");
}

}  // namespace

Result<HttpReply> soiq_structure(const HandlerContext& c, StructureResource what, const std::string& id_text,
                                 const HttpRequest& req) {
  SOIQ_ASSIGN_OR_RETURN(const int64_t id, structure_id(id_text));
  if (what != StructureResource::kRendered && what != StructureResource::kThumbnail && !req.params.empty())
    return invalid_argument("unsupported parameter '" + req.params.front().first + "': this resource takes none")
        .in_field(req.params.front().first);
  switch (what) {
    case StructureResource::kRendered:
      return picture(c, id, false, req);
    case StructureResource::kThumbnail:
      return picture(c, id, true, req);
    case StructureResource::kSeg:
      return seg(c, id, req);
    case StructureResource::kMask:
      return mask(c, id, req);
    case StructureResource::kSurface:
      return surface(c, id);
  }
  return internal_error("unknown structure resource");
}

}  // namespace soiq::server::http
