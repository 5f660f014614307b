// GET /soiq/v1/info: what the query page builds its form from, so that it holds no copy of soiq's
// facts: the feature catalogue (the same as `soiq info --features`), the query options of the one
// table (proto/text/query_options.h: the names a URL gives them, placeholder, default, help) and
// the viewer link soiqd was configured with.
#include <nlohmann/json.hpp>

#include "core/features/feature_catalogue.h"
#include "proto/text/query_options.h"
#include "server/http/http_handlers.h"

namespace soiq::server::http {

Result<HttpReply> soiq_info(const HandlerContext& c, const HttpRequest& req) {
  if (!accepts(req, "application/json")) return HttpReply{406, "application/json", "", {}};
  nlohmann::ordered_json features = nlohmann::ordered_json::array();
  for (const FeatureDef& f : feature_catalogue())
    features.push_back({{"name", f.name},
                        {"family", family_name(f.family)},
                        {"unit", f.unit},
                        {"needs", feature_needs(f)},
                        {"summary", f.summary},
                        {"components", f.components}});
  nlohmann::ordered_json options = nlohmann::ordered_json::array();
  for (const proto_text::QueryOption& o : proto_text::query_options())
    options.push_back({{"name", o.name},
                       {"placeholder", o.value},
                       {"default", o.default_value},
                       {"help", o.meaning},
                       {"repeatable", o.repeatable},
                       {"stage1", o.stage1}});
  const nlohmann::ordered_json body = {{"version", SOIQ_VERSION},
                                       {"features", features},
                                       {"query_options", options},
                                       {"viewer_url", c.engines.config.viewer_url}};
  return HttpReply{200, "application/json", body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), {}};
}

}  // namespace soiq::server::http
