// WADO-RS (PS3.18 10.4) for the DICOM soiq has to give: the SEG of each structure imported from
// DICOM, written on demand (server/app/structure_seg.h) with the stable UIDs QIDO lists
// (structure_seg_uids.h). Image series are kept as voxels, not as DICOM instances: asking for one
// is NOT_FOUND saying so and where to get them.
#include <nlohmann/json.hpp>

#include "dicom/dicom_json_metadata.h"
#include "server/app/structure_seg.h"
#include "server/app/structure_seg_uids.h"
#include "server/http/http_handlers.h"
#include "server/http/multipart.h"

namespace soiq::server::http {
namespace {

constexpr char kExplicitVrLittleEndian[] = "1.2.840.10008.1.2.1";

// Accept admits multipart/related of application/dicom in the transfer syntax soiq writes.
bool accepts_dicom(const HttpRequest& req) {
  if (!req.has_header("Accept")) return true;
  const std::string accept = req.header("Accept");
  size_t from = 0;
  while (from <= accept.size()) {
    size_t comma = accept.find(',', from);
    if (comma == std::string::npos) comma = accept.size();
    const std::string item = accept.substr(from, comma - from);
    const std::string media = item.substr(0, item.find(';'));
    const std::string type = header_parameter(item, "type");
    const std::string syntax = header_parameter(item, "transfer-syntax");
    const bool syntax_ok = syntax.empty() || syntax == "*" || syntax == kExplicitVrLittleEndian;
    if (media.find("*/*") != std::string::npos) return true;
    if (is_multipart_related(media) && (type.empty() || type == "application/dicom") && syntax_ok) return true;
    from = comma + 1;
  }
  return false;
}

// The structure whose SEG series `series_uid` is, in study `study_uid`.
Result<db::StructureRecord> seg_structure(const AppEngines& e, const std::string& study_uid,
                                          const std::string& series_uid) {
  const auto parsed = parse_structure_seg_uid(series_uid);
  if (!parsed || parsed->instance) {
    Result<db::SeriesRecord> image = e.store.get_series(series_uid);
    if (image.ok() && image->study_uid == study_uid)
      return not_found("series " + series_uid +
                       " is kept by soiq as voxels for its features, not as DICOM instances: retrieve its images "
                       "from the PACS or files they came from (soiq's DICOM are the SEG series of its structures)");
    return not_found("series '" + series_uid + "' not found in study '" + study_uid + "'");
  }
  Result<db::StructureRecord> s = e.store.get_structure(parsed->structure_id);
  if (!s.ok() && s.status().code() != StatusCode::kNotFound) return s.status();
  if (!s.ok() || s->study_uid != study_uid || structure_seg_uids(*s).series_uid != series_uid)
    return not_found("series '" + series_uid + "' not found in study '" + study_uid +
                     "' (a structure whose surface changed has new UIDs: query the study's series again)");
  return *s;
}

// The SEGs of `structures`, as Part 10 files, each with its share of the budget, into `reply.held`.
// One task on soiqd's worker pool for them all: waiting for a worker while holding SEGs could
// leave the workers waiting for the budget those SEGs hold. A wait for the budget while holding
// gives up after 30 s (memory_budget.h); a client that has gone stops it.
Result<std::vector<std::string>> segs_of(const AppEngines& e, const std::vector<db::StructureRecord>& structures,
                                         const HttpRequest& req, HttpReply& reply) {
  const std::function<Status()> client_here = stop_when_client_gone(req);
  std::vector<std::string> files;
  auto work = [&]() -> Status {
    for (const db::StructureRecord& s : structures) {
      const StructureSegUids uids = structure_seg_uids(s);
      const auto stop = stop_when_held_too_long(client_here, !reply.held.empty(), 30000,
                                                "the study's SEGs do not fit the memory budget together while other "
                                                "work holds it; retrieve them series by series");
      SOIQ_ASSIGN_OR_RETURN(BudgetedSeg written, structure_seg(e.store, e.features, e.budget, {s.id},
                                                               seg_series_description(s.name), &uids, stop));
      files.push_back(std::move(written.seg.bytes));
      reply.held.push_back(std::move(written.held));
    }
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(e.pool.call(work));
  return files;
}

// The structures of what the path names: one series, or every SEG series of a study.
Result<std::vector<db::StructureRecord>> structures_of(const AppEngines& e, const std::string& study_uid,
                                                       const std::string& series_uid, const std::string& instance_uid) {
  if (!series_uid.empty()) {
    SOIQ_ASSIGN_OR_RETURN(db::StructureRecord s, seg_structure(e, study_uid, series_uid));
    if (!instance_uid.empty() && structure_seg_uids(s).sop_instance_uid != instance_uid)
      return not_found("instance '" + instance_uid + "' not found in series '" + series_uid + "'");
    return std::vector<db::StructureRecord>{s};
  }
  SOIQ_RETURN_IF_ERROR(e.store.get_study(study_uid).status());
  db::SeriesSearch search;
  search.study_uids = {study_uid};
  search.modality = "SEG";
  search.limit = kMaxSegStructures + 1;
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesHit> hits, e.store.search_series(search));
  if (hits.empty())
    return not_found("study '" + study_uid +
                     "' has no structure imported from DICOM, so no SEG to send (its images are kept as voxels)");
  if (int64_t(hits.size()) > kMaxSegStructures)
    return resource_exhausted("study '" + study_uid + "' has more than " + std::to_string(kMaxSegStructures) +
                              " SEG series; retrieve them series by series");
  std::vector<db::StructureRecord> out;
  for (const db::SeriesHit& h : hits) out.push_back(*h.structure);
  return out;
}

std::string instance_url(const HandlerContext& c, const db::StructureRecord& s) {
  const StructureSegUids uids = structure_seg_uids(s);
  return c.base_url + "/studies/" + s.study_uid + "/series/" + uids.series_uid + "/instances/" + uids.sop_instance_uid;
}

}  // namespace

Result<HttpReply> wado(const HandlerContext& c, WadoWhat what, const std::string& study_uid,
                       const std::string& series_uid, const std::string& instance_uid, const HttpRequest& req) {
  const bool metadata = what == WadoWhat::kMetadata;
  const bool bulk = what == WadoWhat::kBulkData;
  if (metadata && !accepts(req, "application/dicom+json") && !accepts(req, "application/json"))
    return HttpReply{406, "application/dicom+json", "", {}};
  if (what == WadoWhat::kInstances && !accepts_dicom(req))
    return HttpReply{
        406,
        std::string("multipart/related; type=\"application/dicom\"; transfer-syntax=") + kExplicitVrLittleEndian,
        "",
        {}};
  if (bulk && !accepts(req, "multipart/related")) return HttpReply{406, "multipart/related", "", {}};
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::StructureRecord> structures,
                        structures_of(c.engines, study_uid, series_uid, instance_uid));
  // Each SEG's bytes stay counted in the budget until the answer holding them is written.
  HttpReply r;
  SOIQ_ASSIGN_OR_RETURN(std::vector<std::string> files, segs_of(c.engines, structures, req, r));
  if (metadata) {
    std::string body = "[";
    for (size_t i = 0; i < files.size(); ++i) {
      SOIQ_ASSIGN_OR_RETURN(const std::string json,
                            dicom::dicom_json_metadata(files[i], instance_url(c, structures[i]) + "/bulkdata"));
      body += (i ? "," : "") + json;
    }
    r.content_type = "application/dicom+json";
    r.body = body + "]";
    r.held.clear();  // the SEGs go with this function; their JSON is small
    return r;
  }
  std::vector<std::string> parts;
  if (bulk) {
    SOIQ_ASSIGN_OR_RETURN(std::string p, dicom::pixel_data_of(files.at(0)));
    parts.push_back(std::move(p));
  } else {
    parts = std::move(files);
  }
  const std::string part_type = bulk ? "application/octet-stream" : "application/dicom";
  WrittenMultipart body = write_multipart_related(std::move(parts), part_type);
  r.content_type = "multipart/related; type=\"" + part_type + "\"; boundary=" + body.boundary;
  r.pieces = std::move(body.pieces);
  return r;
}

}  // namespace soiq::server::http
