// GET /soiq/v1/query/plot: the query's answer as a plot (proto/text/query_plot.h says which
// features, render/plot_picture.h how it is drawn): SVG, or PNG with Accept: image/png. The query
// runs as GET /soiq/v1/query runs it (its arguments, its engine, its cache), so a page that showed
// the rows gets the plot of the same rows from the feature cache.
#include "proto/text/query_plot.h"
#include "render/plot_picture.h"
#include "server/api/query_request.h"
#include "server/http/http_handlers.h"
#include "server/http/soiq_query_args.h"

namespace soiq::server::http {

Result<HttpReply> soiq_query_plot(const HandlerContext& c, const HttpRequest& req) {
  // SVG unless PNG is asked for by name before it.
  render::PictureOptions picture;
  picture.format = render::PictureFormat::kSvg;
  bool acceptable = !req.has_header("Accept");
  for (const std::string& type : accepted_types(req)) {
    if (type == "image/png") picture.format = render::PictureFormat::kPng;
    acceptable = type == "image/png" || type == "image/svg+xml" || type == "image/*" || type == "*/*";
    if (acceptable) break;
  }
  if (!acceptable) return HttpReply{406, "image/svg+xml or image/png", "", {}};
  SOIQ_ASSIGN_OR_RETURN(const v1::QueryRequest request, parse_soiq_query_args(req.params));
  SOIQ_ASSIGN_OR_RETURN(const Query query, parse_query(request, c.engines.config.query_result_cap));
  SOIQ_ASSIGN_OR_RETURN(const QueryAnswer answer, run_query(c.engines, query, req));
  const std::vector<QueryRow>& rows = answer.rows;
  SOIQ_ASSIGN_OR_RETURN(
      const std::vector<proto_text::PlotColumn> columns,
      proto_text::query_plot_columns(request, rows.size(), [&](size_t r, size_t k) -> std::optional<double> {
        if (k >= rows[r].values.size()) return std::nullopt;
        const std::vector<double>& v = rows[r].values[k].values;
        if (v.size() != 1) return std::nullopt;
        return v[0];
      }));
  std::vector<render::PlotAxis> axes;
  for (const proto_text::PlotColumn& col : columns) axes.push_back({col.name, col.unit, col.values});
  SOIQ_ASSIGN_OR_RETURN(std::string bytes, render::plot_picture(axes, "", 720, 480, picture));
  HttpReply r;
  r.content_type = render::media_type(picture.format);
  r.body = std::move(bytes);
  return r;
}

}  // namespace soiq::server::http
