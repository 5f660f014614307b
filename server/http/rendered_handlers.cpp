// WADO-RS rendered and thumbnail resources (PS3.18 10.4.1.1.3, 10.4.1.1.4) of what soiqd's
// DICOMweb lists: each structure's SEG and RT Structure Set (one instance: drawn as the structure
// over its source slice; a SEG's frame: the slice that frame lies on) and the image series kept as
// voxels (an instance: its slice; a series: its middle slice). A study's thumbnail is its first
// structure's, else its first image series'. One picture per request: a frame list of more than
// one is refused.
#include <algorithm>

#include "server/app/structure_object.h"
#include "server/app/structure_object_uids.h"
#include "server/app/structure_render.h"
#include "server/http/http_handlers.h"
#include "server/http/rendered_params.h"

namespace soiq::server::http {
namespace {

HttpReply picture_reply(RenderedPicture&& picture) {
  HttpReply r;
  r.content_type = render::media_type(picture.format);
  r.body = std::move(picture.bytes);
  return r;
}

Result<int64_t> frame_number(const std::string& frames) {
  if (frames.find(',') != std::string::npos)
    return invalid_argument("one frame per rendered request: ask for frames '" + frames + "' one at a time");
  if (frames.empty() || frames.size() > 9 || !std::all_of(frames.begin(), frames.end(), ::isdigit) ||
      std::stoll(frames) < 1)
    return invalid_argument("frame '" + frames + "' is not a frame number (1, 2, ...)");
  return std::stoll(frames);
}

// The picture of one of a structure's objects or one image series of the study.
Result<RenderedPicture> draw_series(const AppEngines& e, const std::string& study_uid, const std::string& series_uid,
                                    const std::string& instance_uid, std::optional<int64_t> frame, RenderAsk ask,
                                    const HttpRequest& req) {
  SOIQ_ASSIGN_OR_RETURN(const std::optional<StructureObjectRef> object,
                        find_structure_object(e.store, study_uid, series_uid, instance_uid));
  if (object) {
    if (frame && object->object == db::StructureObject::kRtStruct)
      return not_found("instance '" + instance_uid + "' is an RT Structure Set: it has no frames");
    const db::StructureRecord& s = object->structure;
    // Over the image its object derives from, in the plane of that image's slices, so a SEG's
    // frame n is drawn on the slice frame n references.
    ask.image = s.source_series_uid;
    if (!s.source_series_uid.empty()) {
      SOIQ_ASSIGN_OR_RETURN(const db::SeriesRecord source, e.store.get_series(s.source_series_uid));
      ask.plane = stacking_plane(source.geometry);
    }
    ask.seg_frame = frame;
    return render_structure(e.store, e.features, e.pool, s.id, ask, stop_when_client_gone(req));
  }
  Result<db::SeriesRecord> series = e.store.get_series(series_uid);
  if (!series.ok() && series.status().code() != StatusCode::kNotFound) return series.status();
  if (!series.ok() || series->study_uid != study_uid)
    return not_found("series '" + series_uid + "' not found in study '" + study_uid + "'");
  int64_t k = std::max<int64_t>(0, series->geometry.dims[2] / 2);
  if (!instance_uid.empty()) {
    const auto& uids = series->slice_instance_uids;
    const auto at = std::find(uids.begin(), uids.end(), instance_uid);
    if (at == uids.end()) return not_found("instance '" + instance_uid + "' not found in series '" + series_uid + "'");
    k = at - uids.begin();
  }
  if (frame && *frame != 1)
    return not_found("instance '" + instance_uid + "' is a single-frame image: it has frame 1 only");
  return render_series_slice(e.store, e.features, e.budget, e.pool, series_uid, k, ask);
}

// A study's thumbnail: its first structure's, else its first image series'.
Result<RenderedPicture> draw_study(const AppEngines& e, const std::string& study_uid, const RenderAsk& ask,
                                   const HttpRequest& req) {
  SOIQ_RETURN_IF_ERROR(e.store.get_study(study_uid).status());
  db::SeriesSearch search;
  search.study_uids = {study_uid};
  search.limit = 64;
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesHit> hits, e.store.search_series(search));
  const db::SeriesHit* chosen = nullptr;
  for (const db::SeriesHit& h : hits)
    if (h.structure && (chosen == nullptr || !chosen->structure)) chosen = &h;
  if (chosen == nullptr && !hits.empty()) chosen = &hits.front();
  if (chosen == nullptr) return not_found("study '" + study_uid + "' has no series to draw");
  const std::string uid = chosen->structure ? structure_object_uids(*chosen->structure, chosen->object).series_uid
                                            : chosen->series.series_uid;
  return draw_series(e, study_uid, uid, "", std::nullopt, ask, req);
}

}  // namespace

Result<HttpReply> wado_rendered(const HandlerContext& c, bool thumbnail, const std::string& study_uid,
                                const std::string& series_uid, const std::string& instance_uid,
                                const std::string& frames, const HttpRequest& req) {
  const std::optional<render::PictureFormat> format = rendered_format(req, false);
  if (!format) return HttpReply{406, "image/jpeg or image/png", "", {}};
  SOIQ_ASSIGN_OR_RETURN(
      RenderAsk ask, rendered_ask(req, RenderedParams::kWado, thumbnail ? std::optional(kThumbnailBox) : std::nullopt));
  ask.picture.format = *format;
  ask.thumbnail = thumbnail;
  std::optional<int64_t> frame;
  if (!frames.empty()) {
    SOIQ_ASSIGN_OR_RETURN(frame, frame_number(frames));
  }
  if (series_uid.empty()) {
    SOIQ_ASSIGN_OR_RETURN(RenderedPicture p, draw_study(c.engines, study_uid, ask, req));
    return picture_reply(std::move(p));
  }
  SOIQ_ASSIGN_OR_RETURN(RenderedPicture p,
                        draw_series(c.engines, study_uid, series_uid, instance_uid, frame, ask, req));
  return picture_reply(std::move(p));
}

}  // namespace soiq::server::http
