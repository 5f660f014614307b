// QIDO-RS (PS3.18 10.6): the query checked whole (qido_query.h), one store search, the hits as
// DICOM JSON (qido_json.h).
#include <nlohmann/json.hpp>

#include "server/http/http_handlers.h"
#include "server/http/qido_json.h"
#include "server/http/qido_query.h"

namespace soiq::server::http {
namespace {

using nlohmann::json;

// Instance queries walk series page by page; past this many series they ask for a narrower query
// rather than read the whole store.
constexpr int kMaxSeriesPagesPerInstanceQuery = 100;

// A SEG series asked for by UID is found by its structure id; the hit is it only when the whole UID
// is the structure's (its surface may have changed since).
bool is_asked_series(const QidoQuery& q, const db::SeriesHit& h) {
  return !q.series.structure_id || series_uid_of(h) == q.series_uid_asked;
}

Result<json> studies(const HandlerContext& c, const QidoQuery& q) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::StudyHit> hits, c.engines.store.search_studies(q.studies));
  json out = json::array();
  for (const db::StudyHit& h : hits) out.push_back(study_json(h, c.base_url, q));
  return out;
}

Result<json> series(const HandlerContext& c, const QidoQuery& q) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesHit> hits, c.engines.store.search_series(q.series));
  json out = json::array();
  for (const db::SeriesHit& h : hits) {
    if (is_asked_series(q, h)) out.push_back(series_json(h, c.base_url, q));
  }
  return out;
}

Result<json> instances(const HandlerContext& c, const QidoQuery& q) {
  json out = json::array();
  int64_t skip = q.offset;
  db::SeriesSearch s = q.series;
  s.offset = 0;
  s.limit = db::kMaxSearchLimit;
  for (int page = 0;; ++page) {
    if (page == kMaxSeriesPagesPerInstanceQuery)
      return resource_exhausted("this instance query walks more than " +
                                std::to_string(kMaxSeriesPagesPerInstanceQuery * db::kMaxSearchLimit) +
                                " series; name a study or series, or query /series first");
    SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesHit> hits, c.engines.store.search_series(s));
    for (const db::SeriesHit& h : hits) {
      if (!is_asked_series(q, h)) continue;
      const int64_t n = instance_count_of(h);
      for (int64_t k = 0; k < n; ++k) {
        const InstanceRef ref{&h, k};
        if (!q.sop_instance_uid.empty() && instance_uid_of(ref) != q.sop_instance_uid) continue;
        if (skip > 0) {
          --skip;
          continue;
        }
        out.push_back(instance_json(ref, c.base_url, q));
        if (int64_t(out.size()) == q.limit) return out;
      }
    }
    if (int64_t(hits.size()) < s.limit) return out;
    s.offset += s.limit;
  }
}

}  // namespace

Result<HttpReply> qido(const HandlerContext& c, QidoLevel level, const std::string& study_uid,
                       const std::string& series_uid, const HttpRequest& req) {
  if (!accepts(req, "application/dicom+json") && !accepts(req, "application/json"))
    return HttpReply{406, "application/dicom+json", "", {}};
  const QueryParams& params = req.params;
  SOIQ_ASSIGN_OR_RETURN(const QidoQuery q,
                        parse_qido(level, study_uid, series_uid, params, c.engines.config.keep_patient_names));
  // A study or series the path names must exist: an empty list would not say the UID is wrong.
  if (!study_uid.empty()) SOIQ_RETURN_IF_ERROR(c.engines.store.get_study(study_uid).status());
  json out = json::array();
  if (!q.matches_nothing) {
    switch (level) {
      case QidoLevel::kStudy: {
        SOIQ_ASSIGN_OR_RETURN(out, studies(c, q));
        break;
      }
      case QidoLevel::kSeries: {
        SOIQ_ASSIGN_OR_RETURN(out, series(c, q));
        break;
      }
      case QidoLevel::kInstance: {
        SOIQ_ASSIGN_OR_RETURN(out, instances(c, q));
        break;
      }
    }
  }
  if (!series_uid.empty() && out.empty() && q.sop_instance_uid.empty() && q.offset == 0)
    return not_found("series '" + series_uid + "' not found in study '" + study_uid + "'");
  HttpReply r;
  r.content_type = "application/dicom+json";
  r.body = out.dump(-1, ' ', false, json::error_handler_t::replace);
  if (q.limit_clamped)
    r.headers.emplace("Warning", "299 soiqd: \"The number of results is limited to " +
                                     std::to_string(db::kMaxSearchLimit) +
                                     " per request; ask for the next ones with offset.\"");
  return r;
}

}  // namespace soiq::server::http
