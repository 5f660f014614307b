// SoiqService's uploads: a surface, an image series, DICOM files. Each reads its client stream up to
// the upload limit, parses from memory, and stores in one transaction.
#include <optional>

#include "db/image_blob.h"
#include "db/surface_blob.h"
#include "server/api/proto_records.h"
#include "server/api/received_dicom_files.h"
#include "server/api/rpc_handling.h"
#include "server/app/dicom_import.h"
#include "server/app/uploaded_files.h"
#include "server/util/temp_dir.h"

namespace soiq::server {
namespace {

// Reads a client stream: the header first, then chunks up to `max_bytes` in all.
template <typename Request, typename Header>
Status read_upload(grpc::ServerReader<Request>* reader, int64_t max_bytes, Header& header, std::string& bytes,
                   const char* what) {
  Request part;
  if (!reader->Read(&part) || part.part_case() != Request::kHeader)
    return invalid_argument(std::string(what) + " upload must start with a header message");
  header = part.header();
  while (reader->Read(&part)) {
    if (part.part_case() != Request::kChunk)
      return invalid_argument(std::string(what) + " upload has a second header; send one header, then chunks");
    if (int64_t(bytes.size() + part.chunk().size()) > max_bytes)
      return resource_exhausted(std::string(what) + " upload is larger than the server's limit of " +
                                std::to_string(max_bytes) + " bytes (soiqd --max-upload-bytes)");
    bytes += part.chunk();
  }
  return ok_status();
}

}  // namespace

grpc::Status SoiqService::UploadSurface(grpc::ServerContext* ctx, grpc::ServerReader<v1::UploadSurfaceRequest>* reader,
                                        v1::UploadSurfaceResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    v1::UploadSurfaceHeader h;
    std::string bytes;
    SOIQ_RETURN_IF_ERROR(read_upload(reader, config_.max_upload_bytes, h, bytes, "surface"));
    db::NewStructure s;
    SOIQ_ASSIGN_OR_RETURN(s.patient, from_proto(h.patient()));
    SOIQ_ASSIGN_OR_RETURN(s.study, from_proto(h.study(), s.patient.patient_id));
    if (h.structure_name().empty()) return invalid_argument("structure_name is required");
    SOIQ_RETURN_IF_ERROR(check_laterality(h.laterality()));
    SOIQ_RETURN_IF_ERROR(check_enum(h.coordinates(), v1::CoordinateSystem_IsValid, "coordinates"));
    s.name = h.structure_name();
    s.laterality = h.laterality();
    s.robust = h.robust();
    SOIQ_ASSIGN_OR_RETURN(ParsedSurface parsed,
                          parse_surface(bytes, h.format(), h.coordinates() == v1::RAS, h.robust(), s.name));
    SOIQ_ASSIGN_OR_RETURN(db::EncodedSurface encoded, db::encode_surface(parsed.mesh));
    s.surface = encoded.info;
    s.surface_blob = std::move(encoded.blob);
    SOIQ_ASSIGN_OR_RETURN(db::AddedStructure added, store_.add_structure(std::move(s)));
    *response->mutable_structure() = to_proto(added.structure);
    response->set_surface_already_stored(added.surface_already_stored);
    response->set_defects(describe(parsed.defects));
    return ok_status();
  });
}

grpc::Status SoiqService::UploadImage(grpc::ServerContext* ctx, grpc::ServerReader<v1::UploadImageRequest>* reader,
                                      v1::UploadImageResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    v1::UploadImageHeader h;
    std::string bytes;
    SOIQ_RETURN_IF_ERROR(read_upload(reader, config_.max_upload_bytes, h, bytes, "image"));
    db::NewSeries s;
    SOIQ_ASSIGN_OR_RETURN(s.patient, from_proto(h.patient()));
    SOIQ_ASSIGN_OR_RETURN(s.study, from_proto(h.study(), s.patient.patient_id));
    if (h.series_uid().empty()) return invalid_argument("series_uid is required");
    if (h.modality().empty()) return invalid_argument("modality is required (e.g. CT, MR, PT)");
    // The decoded image and its compressed blob are admitted against the memory budget as soon as
    // the header tells their size, before a voxel is decoded.
    std::optional<MemoryBudget::Reservation> held;
    ImageDecodeLimits limits;
    limits.max_voxels = config_.max_grid_voxels;
    limits.before_decoding = [&](const ImageGeometry& g, int64_t decode_bytes) -> Status {
      const auto& d = g.dims;
      SOIQ_ASSIGN_OR_RETURN(MemoryBudget::Reservation r,
                            budget_.reserve(decode_bytes + g.voxel_count() * int64_t(sizeof(float)),
                                            "image '" + h.series_uid() + "' of " + std::to_string(d[0]) + "x" +
                                                std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels",
                                            [&] { return stop_status(*ctx); }));
      held = std::move(r);
      return ok_status();
    };
    SOIQ_ASSIGN_OR_RETURN(Image image, parse_image(bytes, h.format(), h.series_uid(), limits));
    SOIQ_ASSIGN_OR_RETURN(db::EncodedImage encoded, db::encode_image(image));
    s.series.series_uid = h.series_uid();
    s.series.study_uid = s.study.study_uid;
    s.series.modality = h.modality();
    s.series.geometry = image.geometry;
    s.series.sha256 = encoded.sha256;
    s.image_blob = std::move(encoded.blob);
    SOIQ_ASSIGN_OR_RETURN(bool replaced, store_.put_series(s));
    *response->mutable_series() = to_proto(s.series);
    response->set_replaced(replaced);
    return ok_status();
  });
}

grpc::Status SoiqService::ImportDicom(grpc::ServerContext* ctx, grpc::ServerReader<v1::ImportDicomRequest>* reader,
                                      v1::ImportDicomResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(TempDir dir, TempDir::create());  // removed with the files on return
    SOIQ_ASSIGN_OR_RETURN(ReceivedFiles files, receive_dicom_files(*reader, dir.path(), config_.max_upload_bytes));
    SOIQ_ASSIGN_OR_RETURN(const DicomImportResult imported, on_pool<DicomImportResult>([&] {
                            return import_dicom_folder(store_, dir.path(), files.paths, config_.max_grid_voxels,
                                                       budget_, [&] { return stop_status(*ctx); });
                          }));
    *response = to_proto(imported);
    response->set_bytes_received(files.bytes);
    return ok_status();
  });
}

}  // namespace soiq::server
