// SoiqService's DICOM-out and PACS handlers: ExportSeg, ExportRtStruct, PacsEcho, PacsFind, PacsPull,
// PacsPush.
// Thin, as the others: validate, call one function of server/ or dicom/, map once.
#include <filesystem>

#include "dicom/pacs_echo.h"
#include "dicom/pacs_find.h"
#include "dicom/pacs_store.h"
#include "server/api/pacs_find_request.h"
#include "server/api/proto_records.h"
#include "server/api/rpc_handling.h"
#include "server/app/dicom_import.h"
#include "server/app/pacs_pull_studies.h"
#include "server/app/structure_rt_struct.h"
#include "server/app/structure_seg.h"
#include "server/util/temp_dir.h"
#include "server/util/temp_file.h"

namespace soiq::server {
namespace {

constexpr size_t kSegChunkBytes = 1 << 20;

v1::SegInfo info_of(const dicom::WrittenSeg& seg, const std::vector<int64_t>& ids, const db::StructureRecord& first) {
  v1::SegInfo i;
  i.set_sop_instance_uid(seg.sop_instance_uid);
  i.set_series_uid(seg.series_uid);
  i.set_referenced_series_uid(first.source_series_uid);
  i.set_study_uid(first.study_uid);
  i.set_segments(int32_t(ids.size()));
  i.set_frames(seg.frame_count);
  i.set_size_bytes(int64_t(seg.bytes.size()));
  return i;
}

v1::RtStructInfo info_of(const BudgetedRtStruct& written, const std::vector<int64_t>& ids) {
  v1::RtStructInfo i;
  const dicom::WrittenRtStruct& rt = written.rt_struct;
  i.set_sop_instance_uid(rt.sop_instance_uid);
  i.set_series_uid(rt.series_uid);
  i.set_referenced_series_uid(written.referenced_series_uid);
  i.set_study_uid(written.study_uid);
  i.set_rois(int32_t(ids.size()));
  i.set_contours(rt.contour_count);
  i.set_points(rt.point_count);
  i.set_size_bytes(int64_t(rt.bytes.size()));
  return i;
}

// Part 10 bytes as a stream of `Response`s: chunks after the info the caller sent.
template <typename Response, typename Writer>
Status write_chunks(const std::string& bytes, Writer* writer) {
  for (size_t at = 0; at < bytes.size(); at += kSegChunkBytes) {
    Response chunk;
    chunk.set_chunk(bytes.substr(at, kSegChunkBytes));
    if (!writer->Write(chunk)) return Status(StatusCode::kCancelled, "the client closed the export");
  }
  return ok_status();
}

}  // namespace

Result<dicom::PacsPeer> SoiqService::pacs() const {
  if (!config_.pacs_peer)
    return failed_precondition("soiqd has no PACS configured: start it with --pacs AE@HOST:PORT (or SOIQ_PACS)");
  return *config_.pacs_peer;
}

grpc::Status SoiqService::ExportSeg(grpc::ServerContext* ctx, const v1::ExportSegRequest* request,
                                    grpc::ServerWriter<v1::ExportSegResponse>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    const std::vector<int64_t> ids(request->structure_ids().begin(), request->structure_ids().end());
    SOIQ_ASSIGN_OR_RETURN(const BudgetedSeg written, on_pool<BudgetedSeg>([&] {
                            return structure_seg(
                                store_, features_, budget_, ids, request->series_description(), nullptr,
                                [&] { return stop_status(*ctx); }, request->oversample());
                          }));
    const dicom::WrittenSeg& seg = written.seg;
    SOIQ_ASSIGN_OR_RETURN(db::StructureRecord first, store_.get_structure(ids.front()));
    v1::ExportSegResponse head;
    *head.mutable_info() = info_of(seg, ids, first);
    if (!writer->Write(head)) return Status(StatusCode::kCancelled, "the client closed the export");
    for (size_t at = 0; at < seg.bytes.size(); at += kSegChunkBytes) {
      v1::ExportSegResponse chunk;
      chunk.set_chunk(seg.bytes.substr(at, kSegChunkBytes));
      if (!writer->Write(chunk)) return Status(StatusCode::kCancelled, "the client closed the export");
    }
    return ok_status();
  });
}

grpc::Status SoiqService::ExportRtStruct(grpc::ServerContext* ctx, const v1::ExportRtStructRequest* request,
                                         grpc::ServerWriter<v1::ExportRtStructResponse>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    const std::vector<int64_t> ids(request->structure_ids().begin(), request->structure_ids().end());
    SOIQ_ASSIGN_OR_RETURN(const BudgetedRtStruct written, on_pool<BudgetedRtStruct>([&] {
                            return structure_rt_struct(store_, features_, budget_, ids, request->series_description(),
                                                       nullptr, [&] { return stop_status(*ctx); });
                          }));
    v1::ExportRtStructResponse head;
    *head.mutable_info() = info_of(written, ids);
    if (!writer->Write(head)) return Status(StatusCode::kCancelled, "the client closed the export");
    return write_chunks<v1::ExportRtStructResponse>(written.rt_struct.bytes, writer);
  });
}

grpc::Status SoiqService::PacsEcho(grpc::ServerContext* ctx, const v1::PacsEchoRequest*,
                                   v1::PacsEchoResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const dicom::PacsPeer peer, pacs());
    const Clock::time_point start = Clock::now();
    SOIQ_RETURN_IF_ERROR(dicom::pacs_echo(peer));
    response->set_pacs(dicom::describe_pacs_peer(peer));
    response->set_milliseconds(ms_since(start));
    return ok_status();
  });
}

grpc::Status SoiqService::PacsFind(grpc::ServerContext* ctx, const v1::PacsFindRequest* request,
                                   v1::PacsFindResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const dicom::PacsPeer peer, pacs());
    SOIQ_ASSIGN_OR_RETURN(const dicom::PacsQuery query, pacs_query_of(*request));
    SOIQ_ASSIGN_OR_RETURN(const std::vector<dicom::PacsMatch> matches, dicom::pacs_find(peer, query));
    for (const dicom::PacsMatch& m : matches) *response->add_matches() = to_proto(m);
    response->set_pacs(dicom::describe_pacs_peer(peer));
    return ok_status();
  });
}

grpc::Status SoiqService::PacsPull(grpc::ServerContext* ctx, const v1::PacsPullRequest* request,
                                   grpc::ServerWriter<v1::PacsPullEvent>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const dicom::PacsPeer peer, pacs());
    SOIQ_ASSIGN_OR_RETURN(TempDir dir, TempDir::create());  // removed with the pulled files on return
    bool client_gone = false;
    auto progress = [&](const PullProgress& p) {
      v1::PacsPullEvent e;
      *e.mutable_progress() = to_proto(p);
      client_gone = ctx->IsCancelled() || !writer->Write(e);
      return !client_gone;
    };
    const PullRequest asked{{request->study_uids().begin(), request->study_uids().end()}, request->patient_id()};
    Result<PulledFiles> pulled = pacs_pull_studies(peer, asked, dir.path(), config_.max_upload_bytes, progress);
    if (client_gone) return Status(StatusCode::kCancelled, "the client cancelled the pull; nothing was imported");
    SOIQ_RETURN_IF_ERROR(pulled.status());
    SOIQ_ASSIGN_OR_RETURN(const DicomImportResult result, on_pool<DicomImportResult>([&] {
                            return import_dicom_folder(
                                store_, dir.path(), pulled->paths, config_.max_grid_voxels, budget_,
                                [&] { return stop_status(*ctx); },
                                {config_.keep_patient_names, request->replace(), config_.keep_instances});
                          }));
    queued_work();
    v1::ImportDicomResponse imported = to_proto(result);
    imported.set_bytes_received(pulled->bytes);
    v1::PacsPullEvent last;
    *last.mutable_imported() = std::move(imported);
    if (!writer->Write(last))
      return Status(StatusCode::kCancelled, "the client left before the import result (the import was stored)");
    return ok_status();
  });
}

grpc::Status SoiqService::PacsPush(grpc::ServerContext* ctx, const v1::PacsPushRequest* request,
                                   v1::PacsPushResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const dicom::PacsPeer peer, pacs());
    const Clock::time_point start = Clock::now();
    const std::vector<int64_t> ids(request->structure_ids().begin(), request->structure_ids().end());
    const auto stop = [&] { return stop_status(*ctx); };
    SOIQ_ASSIGN_OR_RETURN(TempFile file, TempFile::create(".dcm"));
    if (request->object() == v1::PUSHED_OBJECT_RTSTRUCT) {
      SOIQ_ASSIGN_OR_RETURN(const BudgetedRtStruct written, on_pool<BudgetedRtStruct>([&] {
                              return structure_rt_struct(store_, features_, budget_, ids, request->series_description(),
                                                         nullptr, stop);
                            }));
      SOIQ_RETURN_IF_ERROR(file.write(written.rt_struct.bytes));
      SOIQ_RETURN_IF_ERROR(dicom::pacs_store(peer, {file.path()}));
      *response->mutable_rt_struct() = info_of(written, ids);
    } else if (request->object() == v1::PUSHED_OBJECT_SEG) {
      SOIQ_ASSIGN_OR_RETURN(const BudgetedSeg written, on_pool<BudgetedSeg>([&] {
                              return structure_seg(store_, features_, budget_, ids, request->series_description(),
                                                   nullptr, stop);
                            }));
      SOIQ_RETURN_IF_ERROR(file.write(written.seg.bytes));
      SOIQ_RETURN_IF_ERROR(dicom::pacs_store(peer, {file.path()}));
      SOIQ_ASSIGN_OR_RETURN(db::StructureRecord first, store_.get_structure(ids.front()));
      *response->mutable_seg() = info_of(written.seg, ids, first);
    } else {
      return invalid_argument("unknown object " + std::to_string(int(request->object())) +
                              " to push: PUSHED_OBJECT_SEG or PUSHED_OBJECT_RTSTRUCT");
    }
    response->set_pacs(dicom::describe_pacs_peer(peer));
    response->set_milliseconds(ms_since(start));
    return ok_status();
  });
}

}  // namespace soiq::server
