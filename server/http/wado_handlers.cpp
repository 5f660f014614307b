// WADO-RS (PS3.18 10.4) for the DICOM soiq has to give: the SEG of each structure imported from
// DICOM, written on demand (server/app/structure_seg.h) with the stable UIDs QIDO lists
// (structure_seg_uids.h), and the original instances of image series that soiqd kept at import
// (wado_images.h). A study's retrieval and metadata hold both.
#include <nlohmann/json.hpp>

#include "dicom/dicom_json_metadata.h"
#include "server/app/structure_seg.h"
#include "server/app/structure_seg_uids.h"
#include "server/http/http_handlers.h"
#include "server/http/multipart.h"
#include "server/http/wado_images.h"

namespace soiq::server::http {
namespace {

constexpr char kExplicitVrLittleEndian[] = "1.2.840.10008.1.2.1";

// The structure whose SEG series `series_uid` is, in study `study_uid`.
Result<db::StructureRecord> seg_structure(const AppEngines& e, const std::string& study_uid,
                                          const std::string& series_uid) {
  const auto parsed = parse_structure_seg_uid(series_uid);
  if (!parsed || parsed->instance)
    return not_found("series '" + series_uid + "' not found in study '" + study_uid + "'");
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
  db::SeriesSearch search;
  search.study_uids = {study_uid};
  search.modality = "SEG";
  search.limit = kMaxSegStructures + 1;
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesHit> hits, e.store.search_series(search));
  if (int64_t(hits.size()) > kMaxSegStructures)
    return resource_exhausted("study '" + study_uid + "' has more than " + std::to_string(kMaxSegStructures) +
                              " SEG series; retrieve them series by series");
  std::vector<db::StructureRecord> out;
  for (const db::SeriesHit& h : hits) out.push_back(*h.structure);
  return out;
}

// True for a series uid that names an image series rather than a structure's SEG.
bool is_image_series(const std::string& series_uid) {
  const auto parsed = parse_structure_seg_uid(series_uid);
  return !parsed || parsed->instance;
}

Result<HttpReply> not_acceptable_dicom() {
  return HttpReply{
      406,
      std::string("multipart/related; type=\"application/dicom\"; transfer-syntax=") + kExplicitVrLittleEndian,
      "",
      {}};
}

// An image series of kept instances, or one instance of it.
Result<HttpReply> wado_image(const HandlerContext& c, WadoWhat what, const std::string& study_uid,
                             const std::string& series_uid, const std::string& instance_uid, const std::string& frames,
                             const HttpRequest& req) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::InstanceRecord> kept,
                        kept_series_instances(c.engines, study_uid, series_uid, instance_uid));
  switch (what) {
    case WadoWhat::kMetadata: {
      std::string body = "[";
      for (size_t i = 0; i < kept.size(); ++i) body += (i ? "," : "") + kept_instance_metadata(c, study_uid, kept[i]);
      return HttpReply{200, "application/dicom+json", body + "]", {}};
    }
    case WadoWhat::kInstances: {
      const InstanceSyntax syntax = instance_syntax(req);
      if (syntax == InstanceSyntax::kNotAcceptable) return not_acceptable_dicom();
      return send_instances(c, kept, {}, syntax, req);
    }
    case WadoWhat::kBulkData:
      return send_frames(c, kept.at(0), "", req);
    case WadoWhat::kFrames:
      return send_frames(c, kept.at(0), frames, req);
  }
  return internal_error("unknown WADO-RS resource");
}

std::string instance_url(const HandlerContext& c, const db::StructureRecord& s) {
  const StructureSegUids uids = structure_seg_uids(s);
  return c.base_url + "/studies/" + s.study_uid + "/series/" + uids.series_uid + "/instances/" + uids.sop_instance_uid;
}

}  // namespace

Result<HttpReply> wado(const HandlerContext& c, WadoWhat what, const std::string& study_uid,
                       const std::string& series_uid, const std::string& instance_uid, const std::string& frames,
                       const HttpRequest& req) {
  const bool metadata = what == WadoWhat::kMetadata;
  const bool bulk = what == WadoWhat::kBulkData;
  if (metadata && !accepts(req, "application/dicom+json") && !accepts(req, "application/json"))
    return HttpReply{406, "application/dicom+json", "", {}};
  if (what == WadoWhat::kInstances && instance_syntax(req) == InstanceSyntax::kNotAcceptable)
    return not_acceptable_dicom();
  if (!series_uid.empty() && is_image_series(series_uid))
    return wado_image(c, what, study_uid, series_uid, instance_uid, frames, req);
  if (what == WadoWhat::kFrames)
    return Status(
        StatusCode::kUnimplemented,
        "a SEG's frames are 1 bit per pixel and not byte-aligned: retrieve the SEG instance, or its bulkdata");
  if (bulk && !accepts(req, "multipart/related")) return HttpReply{406, "multipart/related", "", {}};
  std::vector<db::InstanceRecord> images;
  if (series_uid.empty()) {
    SOIQ_RETURN_IF_ERROR(c.engines.store.get_study(study_uid).status());
    SOIQ_ASSIGN_OR_RETURN(images, kept_study_instances(c.engines, study_uid));
  }
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::StructureRecord> structures,
                        structures_of(c.engines, study_uid, series_uid, instance_uid));
  if (images.empty() && structures.empty())
    return not_found("study '" + study_uid +
                     "' has neither an image series whose DICOM instances soiqd kept nor a structure imported from "
                     "DICOM, so no DICOM to send");
  // Each SEG's bytes stay counted in the budget until the answer holding them is written.
  HttpReply r;
  SOIQ_ASSIGN_OR_RETURN(std::vector<std::string> files, segs_of(c.engines, structures, req, r));
  if (metadata) {
    std::string body = "[";
    for (const db::InstanceRecord& i : images)
      body += (body.size() > 1 ? "," : "") + kept_instance_metadata(c, study_uid, i);
    for (size_t i = 0; i < files.size(); ++i) {
      SOIQ_ASSIGN_OR_RETURN(const std::string json,
                            dicom::dicom_json_metadata(files[i], instance_url(c, structures[i]) + "/bulkdata"));
      body += (body.size() > 1 ? "," : "") + json;
    }
    r.content_type = "application/dicom+json";
    r.body = body + "]";
    r.held.clear();  // the SEGs go with this function; their JSON is small
    return r;
  }
  if (what == WadoWhat::kInstances) {
    SOIQ_ASSIGN_OR_RETURN(HttpReply sent, send_instances(c, images, std::move(files), instance_syntax(req), req));
    for (MemoryBudget::Reservation& h : r.held) sent.held.push_back(std::move(h));
    return sent;
  }
  std::vector<std::string> parts;
  SOIQ_ASSIGN_OR_RETURN(std::string p, dicom::pixel_data_of(files.at(0)));
  parts.push_back(std::move(p));
  WrittenMultipart body = write_multipart_related(std::move(parts), "application/octet-stream");
  r.content_type = "multipart/related; type=\"application/octet-stream\"; boundary=" + body.boundary;
  r.pieces = std::move(body.pieces);
  return r;
}

}  // namespace soiq::server::http
