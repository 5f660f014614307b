// WADO-RS (PS3.18 10.4) for the DICOM soiq has to give: the SEG and the RT Structure Set of each
// structure imported from DICOM, written on demand (server/app/structure_object.h) with the stable
// UIDs QIDO lists (structure_object_uids.h), and the original instances of image series that
// soiqd kept at import (wado_images.h). A study's retrieval and metadata hold them all.
#include <nlohmann/json.hpp>

#include "dicom/dicom_json_metadata.h"
#include "server/app/structure_object.h"
#include "server/app/structure_object_uids.h"
#include "server/app/structure_seg.h"
#include "server/http/http_handlers.h"
#include "server/http/multipart.h"
#include "server/http/wado_images.h"

namespace soiq::server::http {
namespace {

constexpr char kExplicitVrLittleEndian[] = "1.2.840.10008.1.2.1";

// The structures' objects, as Part 10 files, each with its share of the budget, into `reply.held`.
// One task on soiqd's worker pool for them all: waiting for a worker while holding objects could
// leave the workers waiting for the budget those objects hold. A wait for the budget while holding
// gives up after 30 s (memory_budget.h); a client that has gone stops it.
Result<std::vector<std::string>> files_of(const AppEngines& e, const std::vector<StructureObjectRef>& objects,
                                          const HttpRequest& req, HttpReply& reply) {
  const std::function<Status()> client_here = stop_when_client_gone(req);
  std::vector<std::string> files;
  auto work = [&]() -> Status {
    for (const StructureObjectRef& o : objects) {
      const auto stop = stop_when_held_too_long(client_here, !reply.held.empty(), 30000,
                                                "the study's SEGs and RT Structure Sets do not fit the memory budget "
                                                "together while other work holds it; retrieve them series by series");
      SOIQ_ASSIGN_OR_RETURN(WrittenStructureObject written,
                            write_structure_object(e.store, e.features, e.budget, o, stop));
      files.push_back(std::move(written.bytes));
      reply.held.push_back(std::move(written.held));
    }
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(e.pool.call(work));
  return files;
}

// The structure objects of what the path names: one series, or every structure's SEG and RT
// Structure Set series in a study (a structure's together, as QIDO lists them).
Result<std::vector<StructureObjectRef>> objects_of(const AppEngines& e, const std::string& study_uid,
                                                   const std::string& series_uid, const std::string& instance_uid) {
  if (!series_uid.empty()) {
    SOIQ_ASSIGN_OR_RETURN(const std::optional<StructureObjectRef> o,
                          find_structure_object(e.store, study_uid, series_uid, instance_uid));
    if (!o) return not_found("series '" + series_uid + "' not found in study '" + study_uid + "'");
    return std::vector<StructureObjectRef>{*o};
  }
  db::SeriesSearch search;
  search.study_uids = {study_uid};
  search.object = db::StructureObject::kSeg;  // one hit per structure
  search.limit = kMaxSegStructures + 1;
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesHit> hits, e.store.search_series(search));
  if (int64_t(hits.size()) > kMaxSegStructures)
    return resource_exhausted("study '" + study_uid + "' has more than " + std::to_string(kMaxSegStructures) +
                              " SEG series; retrieve them series by series");
  std::vector<StructureObjectRef> out;
  for (const db::SeriesHit& h : hits)
    for (const db::StructureObject o : db::kStructureObjects) out.push_back({*h.structure, o});
  return out;
}

// True for a series uid that names an image series rather than one of a structure's objects.
bool is_image_series(const std::string& series_uid) {
  const auto parsed = parse_structure_object_uid(series_uid);
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

std::string instance_url(const HandlerContext& c, const StructureObjectRef& o) {
  const StructureObjectUids uids = structure_object_uids(o.structure, o.object);
  return c.base_url + "/studies/" + o.structure.study_uid + "/series/" + uids.series_uid + "/instances/" +
         uids.sop_instance_uid;
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
  // Frames and bulk data name an instance, so the series UID is a structure object's here.
  const std::optional<ParsedStructureUid> object = parse_structure_object_uid(series_uid);
  if ((what == WadoWhat::kFrames || bulk) && object && object->object == db::StructureObject::kRtStruct)
    return not_found("instance '" + instance_uid +
                     "' is an RT Structure Set: it has no pixel data or frames; retrieve the instance or its metadata");
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
  SOIQ_ASSIGN_OR_RETURN(const std::vector<StructureObjectRef> structures,
                        objects_of(c.engines, study_uid, series_uid, instance_uid));
  if (images.empty() && structures.empty())
    return not_found("study '" + study_uid +
                     "' has neither an image series whose DICOM instances soiqd kept nor a structure imported from "
                     "DICOM, so no DICOM to send");
  // Each object's bytes stay counted in the budget until the answer holding them is written.
  HttpReply r;
  SOIQ_ASSIGN_OR_RETURN(std::vector<std::string> files, files_of(c.engines, structures, req, r));
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
    r.held.clear();  // the objects go with this function; their JSON is small
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
