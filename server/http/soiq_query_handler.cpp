// GET /soiq/v1/query: soiq's two-stage query over HTTP, with `soiq query`'s options as query
// arguments (soiq_query_args.h), checked by the same parse_query as the gRPC call and run by the
// same engine. The rows come as JSON ({"columns", "rows", "summary"}), with Accept: text/csv as the
// CSV `soiq query --format csv` prints (the same header, the same numbers, %.10g), or, with Accept:
// application/x-ndjson, as soiqd computes them: one JSON object per line, {"columns"} first, then
// {"row"} each, then {"summary"}, or {"error"} when the query fails after its first line (the
// query page shows rows as they come). A whole answer has one order: the query's, else by structure
// id; a streamed one has the query's order when it has one (the engine then sends rows sorted),
// else the order they were ready in.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "proto/text/query_columns.h"
#include "server/api/query_request.h"
#include "server/app/structure_object_uids.h"
#include "server/http/http_handlers.h"
#include "server/http/soiq_query_args.h"

namespace soiq::server::http {
namespace {

// Ordered: a row's keys in its columns' order.
using ordered_json = nlohmann::ordered_json;  // columns keep their query order

ordered_json number_json(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(); }

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

ordered_json row_json(const QueryRow& r, const proto_text::QueryColumns& columns) {
  const size_t first_feature = proto_text::structure_columns().size();
  ordered_json row = {{"id", r.structure.id},
                      {"patient_id", r.structure.patient_id},
                      {"study_uid", r.structure.study_uid},
                      {"name", r.structure.name},
                      {"laterality", r.structure.laterality}};
  // The SEG QIDO lists for a structure imported from DICOM, for the page's viewer link ({seg_series}).
  row["seg_series_uid"] = r.structure.source_series_uid.empty()
                              ? ""
                              : structure_object_uids(r.structure, db::StructureObject::kSeg).series_uid;
  for (size_t k = 0; k < columns.value_at.size(); ++k) {
    const std::string& name = columns.header[first_feature + k];
    const size_t at = columns.value_at[k];
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
  return row;
}

std::string json_text(const ordered_json& j) { return j.dump(-1, ' ', false, ordered_json::error_handler_t::replace); }

// The NDJSON answer: each row written as the engine hands it over. A client that has gone stops
// the query at its next row.
Result<HttpReply> stream_query(const HttpRequest& req, const AppEngines& engines, const Query& query,
                               const proto_text::QueryColumns& columns, const std::function<Status()>& stop) {
  SOIQ_RETURN_IF_ERROR(req.start_chunks("application/x-ndjson"));
  SOIQ_RETURN_IF_ERROR(req.send_chunk(json_text({{"columns", columns.header}}) + "\n"));
  QueryOutput out;
  out.progress = [](const QueryProgress&) { return ok_status(); };
  out.row = [&](QueryRow&& r) { return req.send_chunk(json_text({{"row", row_json(r, columns)}}) + "\n"); };
  const Result<QuerySummary> summary = engines.queries.run(query, stop, out);
  if (!summary.ok()) {
    if (summary.status().code() == StatusCode::kCancelled && req.client_gone()) return summary.status();
    ordered_json error = {{"code", status_code_name(summary.status().code())}, {"message", summary.status().message()}};
    if (!summary.status().field().empty()) {
      error["field"] = summary.status().field();
      error["reason"] = summary.status().reason();
    }
    SOIQ_RETURN_IF_ERROR(req.send_chunk(json_text({{"error", error}}) + "\n"));
  } else {
    SOIQ_RETURN_IF_ERROR(req.send_chunk(json_text({{"summary", summary_json(*summary)}}) + "\n"));
  }
  HttpReply reply;
  reply.chunked = true;
  return reply;
}

}  // namespace

Result<HttpReply> soiq_query(const HandlerContext& c, const HttpRequest& req) {
  // text/csv and NDJSON only when asked for by name; JSON otherwise.
  const std::string accept = req.header("Accept");
  const bool csv = accept.find("text/csv") != std::string::npos;
  const bool ndjson = accept.find("application/x-ndjson") != std::string::npos;
  if (!csv && !ndjson && !accepts(req, "application/json"))
    return HttpReply{406, "application/json, application/x-ndjson or text/csv", "", {}};
  const std::vector<std::pair<std::string, std::string>>& args = req.params;
  SOIQ_ASSIGN_OR_RETURN(const v1::QueryRequest request, parse_soiq_query_args(args));
  SOIQ_ASSIGN_OR_RETURN(const Query query, parse_query(request, c.engines.config.query_result_cap));
  const proto_text::QueryColumns columns = proto_text::query_columns(request);
  // A client that has gone stops the query: its conversions are not worth finishing.
  if (ndjson && req.start_chunks) return stream_query(req, c.engines, query, columns, stop_when_client_gone(req));
  SOIQ_ASSIGN_OR_RETURN(QueryAnswer answer, run_query(c.engines, query, req));
  std::vector<QueryRow>& rows = answer.rows;
  const QuerySummary& summary = answer.summary;
  // The engine streams rows as their features are ready; a whole answer has one order: the query's,
  // else by structure id.
  if (!query.order_by)
    std::stable_sort(rows.begin(), rows.end(),
                     [](const QueryRow& a, const QueryRow& b) { return a.structure.id < b.structure.id; });

  const std::vector<std::string>& header = columns.header;
  HttpReply reply;
  if (csv) {
    std::string body = proto_text::csv_line(header);
    for (const QueryRow& r : rows) {
      std::vector<std::string> fields = {std::to_string(r.structure.id), r.structure.patient_id, r.structure.study_uid,
                                         r.structure.name, r.structure.laterality};
      for (const size_t at : columns.value_at)
        fields.push_back(at < r.values.size() ? proto_text::csv_numbers(r.values[at].values) : "");
      body += proto_text::csv_line(fields);
    }
    reply.content_type = "text/csv; charset=utf-8";
    reply.body = std::move(body);
    return reply;
  }
  if (ndjson) {  // HEAD: the lines a GET would stream, as one body
    std::string body = json_text({{"columns", header}}) + "\n";
    for (const QueryRow& r : rows) body += json_text({{"row", row_json(r, columns)}}) + "\n";
    reply.content_type = "application/x-ndjson";
    reply.body = body + json_text({{"summary", summary_json(summary)}}) + "\n";
    return reply;
  }
  ordered_json out_rows = ordered_json::array();
  for (const QueryRow& r : rows) out_rows.push_back(row_json(r, columns));
  reply.content_type = "application/json";
  reply.body = json_text({{"columns", header}, {"rows", out_rows}, {"summary", summary_json(summary)}});
  return reply;
}

}  // namespace soiq::server::http
