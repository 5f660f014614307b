// SoiqService's uploads: a surface, an image series, DICOM files. Each reads its client stream up to
// the upload limit, checks the header's fields, and hands the bytes to its app engine
// (server/app/upload_surface.h, upload_image.h, dicom_import.h), which parses from memory and
// stores in one transaction.
#include <algorithm>

#include "server/api/proto_records.h"
#include "server/api/received_dicom_files.h"
#include "server/api/rpc_handling.h"
#include "server/app/dicom_import.h"
#include "server/app/memory_budget.h"
#include "server/app/modality_names.h"
#include "server/app/upload_image.h"
#include "server/app/upload_surface.h"
#include "server/util/temp_dir.h"

namespace soiq::server {
namespace {

// Read() returns false both when the client ended its stream and when it cancelled the call
// (Ctrl-C, a lost connection). A cancelled stream's bytes are a prefix of the file, which may still
// parse (an OBJ cut after a face, DICOM files cut between two files) and must not be stored.
Status stream_complete(const grpc::ServerContext& ctx, const char* what) {
  if (!ctx.IsCancelled()) return ok_status();
  return Status(StatusCode::kCancelled, std::string(what) + " upload was cancelled by the client before it ended");
}

// Reads a client stream: the header first, then chunks up to `max_bytes` in all. The bytes are
// counted in the memory budget before they are kept: the buffer grows by doubling (from 4 MiB), and
// each larger buffer is reserved before it is made, the smaller one given back once it is gone.
// `held` keeps the count while the caller uses the bytes.
template <typename Request, typename Header>
Status read_upload(const grpc::ServerContext& ctx, grpc::ServerReader<Request>* reader, int64_t max_bytes,
                   MemoryBudget& budget, Header& header, std::string& bytes, MemoryBudget::Reservation& held,
                   const char* what) {
  Request part;
  if (!reader->Read(&part) || part.part_case() != Request::kHeader)
    return invalid_argument(std::string(what) + " upload must start with a header message");
  header = part.header();
  while (reader->Read(&part)) {
    if (part.part_case() != Request::kChunk)
      return invalid_argument(std::string(what) + " upload has a second header; send one header, then chunks");
    const int64_t need = int64_t(bytes.size() + part.chunk().size());
    if (need > max_bytes)
      return resource_exhausted(std::string(what) + " upload is larger than the server's limit of " +
                                std::to_string(max_bytes) + " bytes (soiqd --max-upload-bytes)");
    if (need > held.bytes()) {
      const int64_t grown = std::min(max_bytes, std::max({need, 2 * held.bytes(), int64_t(4) << 20}));
      SOIQ_ASSIGN_OR_RETURN(
          MemoryBudget::Reservation bigger,
          budget.reserve(
              grown, std::string(what) + " upload of " + std::to_string(need) + "+ bytes",
              stop_when_held_too_long([&ctx] { return stop_status(ctx); }, held.bytes() > 0, 30000,
                                      std::string(what) + " upload does not fit the memory budget while other work "
                                                          "holds it; try again later"),
              "send a smaller file, or raise the budget"));
      bytes.reserve(size_t(grown));
      held = std::move(bigger);
    }
    bytes += part.chunk();
  }
  return stream_complete(ctx, what);
}

// The header's fields, checked in the order a client fixes them: patient, study, then the rest.
Result<SurfaceUpload> surface_upload_of(const v1::UploadSurfaceHeader& h) {
  SurfaceUpload u;
  SOIQ_ASSIGN_OR_RETURN(u.patient, from_proto(h.patient()));
  SOIQ_ASSIGN_OR_RETURN(u.study, from_proto(h.study(), u.patient.patient_id));
  if (h.structure_name().empty()) return invalid_argument("is required").in_field("structure_name");
  SOIQ_RETURN_IF_ERROR(check_text(h.structure_name(), kMaxNameBytes).in_field("structure_name"));
  SOIQ_RETURN_IF_ERROR(check_laterality(h.laterality()).in_field("laterality"));
  SOIQ_RETURN_IF_ERROR(check_enum(h.coordinates(), v1::CoordinateSystem_IsValid, "coordinates"));
  u.structure_name = h.structure_name();
  u.laterality = h.laterality();
  u.format = h.format();
  u.ras = h.coordinates() == v1::RAS;
  u.robust = h.robust();
  return u;
}

Result<ImageUpload> image_upload_of(const v1::UploadImageHeader& h) {
  ImageUpload u;
  SOIQ_ASSIGN_OR_RETURN(u.patient, from_proto(h.patient()));
  SOIQ_ASSIGN_OR_RETURN(u.study, from_proto(h.study(), u.patient.patient_id));
  if (h.series_uid().empty()) return invalid_argument("series_uid is required");
  if (h.modality().empty()) return invalid_argument("modality is required (e.g. CT, MR, PT)");
  u.series_uid = h.series_uid();
  u.modality = dicom_modality(h.modality());
  u.format = h.format();
  return u;
}

}  // namespace

grpc::Status SoiqService::UploadSurface(grpc::ServerContext* ctx, grpc::ServerReader<v1::UploadSurfaceRequest>* reader,
                                        v1::UploadSurfaceResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    v1::UploadSurfaceHeader h;
    std::string bytes;
    MemoryBudget::Reservation held;
    SOIQ_RETURN_IF_ERROR(read_upload(*ctx, reader, config_.max_upload_bytes, budget_, h, bytes, held, "surface"));
    SOIQ_ASSIGN_OR_RETURN(const SurfaceUpload upload, surface_upload_of(h));
    SOIQ_ASSIGN_OR_RETURN(const UploadedSurface stored, upload_surface(store_, upload, bytes));
    *response->mutable_structure() = to_proto(stored.added.structure);
    response->set_surface_already_stored(stored.added.surface_already_stored);
    response->set_defects(describe(stored.defects));
    queued_work();
    return ok_status();
  });
}

grpc::Status SoiqService::UploadImage(grpc::ServerContext* ctx, grpc::ServerReader<v1::UploadImageRequest>* reader,
                                      v1::UploadImageResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    v1::UploadImageHeader h;
    std::string bytes;
    MemoryBudget::Reservation held;
    SOIQ_RETURN_IF_ERROR(read_upload(*ctx, reader, config_.max_upload_bytes, budget_, h, bytes, held, "image"));
    SOIQ_ASSIGN_OR_RETURN(const ImageUpload upload, image_upload_of(h));
    SOIQ_ASSIGN_OR_RETURN(const UploadedImage stored, upload_image(store_, budget_, config_.max_grid_voxels, upload,
                                                                   bytes, [&] { return stop_status(*ctx); }));
    *response->mutable_series() = to_proto(stored.series);
    response->set_replaced(stored.replaced);
    queued_work();
    return ok_status();
  });
}

grpc::Status SoiqService::ImportDicom(grpc::ServerContext* ctx, grpc::ServerReader<v1::ImportDicomRequest>* reader,
                                      v1::ImportDicomResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(TempDir dir, TempDir::create());  // removed with the files on return
    SOIQ_ASSIGN_OR_RETURN(ReceivedFiles files, receive_dicom_files(*reader, dir.path(), config_.max_upload_bytes));
    SOIQ_RETURN_IF_ERROR(stream_complete(*ctx, "DICOM"));
    SOIQ_ASSIGN_OR_RETURN(const DicomImportResult imported, on_pool<DicomImportResult>([&] {
                            return import_dicom_folder(
                                store_, dir.path(), files.paths, config_.max_grid_voxels, budget_,
                                [&] { return stop_status(*ctx); },
                                {config_.keep_patient_names, files.replace, config_.keep_instances});
                          }));
    *response = to_proto(imported);
    response->set_bytes_received(files.bytes);
    queued_work();
    return ok_status();
  });
}

}  // namespace soiq::server
