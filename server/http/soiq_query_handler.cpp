// GET /soiq/v1/query: soiq's two-stage query over HTTP, with `soiq query`'s options as query
// arguments (soiq_query_args.h), checked by the same parse_query as the gRPC call and run by the
// same engine. The rows come as JSON ({"columns", "rows", "summary"}) or, with Accept: text/csv,
// as the CSV `soiq query --format csv` prints: the same header, the same numbers (%.10g). Without
// order-by the rows are by structure id (the command line prints them as they are computed).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "proto/text/feature_expression.h"
#include "server/api/query_request.h"
#include "server/http/http_handlers.h"
#include "server/http/soiq_query_args.h"

namespace soiq::server::http {
namespace {

// Ordered: a row's keys in its columns' order.
using ordered_json = nlohmann::ordered_json;  // columns keep their query order

std::string number_text(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

ordered_json number_json(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(); }

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The feature columns, as `soiq query` names them: where's, select's, order_by's (feature_text),
// each name once (its first position).
std::vector<std::pair<std::string, size_t>> feature_columns(const v1::QueryRequest& r) {
  std::vector<std::string> all;
  for (const auto& p : r.where()) all.push_back(proto_text::feature_text(p.feature()));
  for (const auto& f : r.select()) all.push_back(proto_text::feature_text(f));
  if (r.has_order_by()) all.push_back(proto_text::feature_text(r.order_by()));
  std::vector<std::pair<std::string, size_t>> out;
  for (size_t i = 0; i < all.size(); ++i) {
    bool first = true;
    for (const auto& [name, at] : out) first = first && name != all[i];
    if (first) out.emplace_back(all[i], i);
  }
  return out;
}

ordered_json summary_json(const QuerySummary& s) {
  ordered_json skipped = ordered_json::array();
  for (const QuerySkip& k : s.skipped)
    skipped.push_back({{"reason", k.reason}, {"count", k.count}, {"structure_ids", k.structure_ids}});
  return {{"stage1_candidates", s.stage1_candidates},
          {"computed", s.computed},
          {"cache_hits", s.cache_hits},
          {"matched", s.matched},
          {"returned", s.returned},
          {"failed", s.failed},
          {"skipped", skipped},
          {"stage1_ms", s.stage1_ms},
          {"stage2_ms", s.stage2_ms},
          {"total_ms", s.total_ms}};
}

}  // namespace

Result<HttpReply> soiq_query(const HandlerContext& c, const HttpRequest& req) {
  // text/csv only when asked for by name; JSON otherwise.
  const bool csv = req.has_header("Accept") && req.header("Accept").find("text/csv") != std::string::npos;
  if (!csv && !accepts(req, "application/json")) return HttpReply{406, "application/json or text/csv", "", {}};
  const std::vector<std::pair<std::string, std::string>>& args = req.params;
  SOIQ_ASSIGN_OR_RETURN(const v1::QueryRequest request, parse_soiq_query_args(args));
  SOIQ_ASSIGN_OR_RETURN(const Query query, parse_query(request, c.engines.config.query_result_cap));
  std::vector<QueryRow> rows;
  QueryOutput out;
  out.progress = [](const QueryProgress&) { return ok_status(); };
  out.row = [&](QueryRow&& r) {
    rows.push_back(std::move(r));
    return ok_status();
  };
  // A client that has gone stops the query: its conversions are not worth finishing.
  const auto stop = [&req]() -> Status {
    return req.client_gone() ? Status(StatusCode::kCancelled, "the HTTP client closed its connection") : ok_status();
  };
  SOIQ_ASSIGN_OR_RETURN(const QuerySummary summary, c.engines.queries.run(query, stop, out));
  // The engine streams rows as their features are ready; a whole answer has one order: the query's,
  // else by structure id.
  if (!query.order_by)
    std::stable_sort(rows.begin(), rows.end(),
                     [](const QueryRow& a, const QueryRow& b) { return a.structure.id < b.structure.id; });

  const auto columns = feature_columns(request);
  std::vector<std::string> header = {"id", "patient_id", "study_uid", "name", "laterality"};
  for (const auto& [name, at] : columns) header.push_back(name);
  HttpReply reply;
  if (csv) {
    std::string body;
    for (size_t i = 0; i < header.size(); ++i) body += (i ? "," : "") + csv_field(header[i]);
    body += "\n";
    for (const QueryRow& r : rows) {
      body += std::to_string(r.structure.id) + "," + csv_field(r.structure.patient_id) + "," +
              csv_field(r.structure.study_uid) + "," + csv_field(r.structure.name) + "," +
              csv_field(r.structure.laterality);
      for (const auto& [name, at] : columns) {
        body += ",";
        if (at >= r.values.size()) continue;
        const std::vector<double>& v = r.values[at].values;
        for (size_t k = 0; k < v.size(); ++k) body += (k ? ";" : "") + number_text(v[k]);
      }
      body += "\n";
    }
    reply.content_type = "text/csv; charset=utf-8";
    reply.body = std::move(body);
    return reply;
  }
  ordered_json out_rows = ordered_json::array();
  for (const QueryRow& r : rows) {
    ordered_json row = {{"id", r.structure.id},
                {"patient_id", r.structure.patient_id},
                {"study_uid", r.structure.study_uid},
                {"name", r.structure.name},
                {"laterality", r.structure.laterality}};
    for (const auto& [name, at] : columns) {
      if (at >= r.values.size() || r.values[at].values.empty()) {
        row[name] = nullptr;
      } else if (r.values[at].values.size() == 1) {
        row[name] = number_json(r.values[at].values[0]);
      } else {
        ordered_json a = ordered_json::array();
        for (const double v : r.values[at].values) a.push_back(number_json(v));
        row[name] = a;
      }
    }
    out_rows.push_back(std::move(row));
  }
  reply.content_type = "application/json";
  reply.body = ordered_json({{"columns", header}, {"rows", out_rows}, {"summary", summary_json(summary)}})
                   .dump(-1, ' ', false, ordered_json::error_handler_t::replace);
  return reply;
}

}  // namespace soiq::server::http
