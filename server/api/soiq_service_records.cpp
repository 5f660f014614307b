// SoiqService's reads and deletes of stored records: patients, studies, structures, surfaces.
#include <algorithm>

#include "server/api/proto_records.h"
#include "server/api/rpc_handling.h"
#include "server/app/stored_surface_bytes.h"

namespace soiq::server {
namespace {

constexpr size_t kDownloadChunkBytes = 1 << 20;  // download chunks: well under gRPC's 4 MiB message limit

db::PageRequest page_of(int32_t size, const std::string& token) {
  db::PageRequest p;
  p.page_size = size <= 0 ? 100 : std::min(size, 1000);
  p.page_token = token;
  return p;
}

}  // namespace

grpc::Status SoiqService::ListPatients(grpc::ServerContext* ctx, const v1::ListPatientsRequest* request,
                                       v1::ListPatientsResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_RETURN_IF_ERROR(check_sex(request->sex()).in_field("sex"));
    db::PatientFilter f{request->patient_id_glob(), request->sex()};
    SOIQ_ASSIGN_OR_RETURN(auto page, store_.list_patients(f, page_of(request->page_size(), request->page_token())));
    for (const auto& p : page.items) *response->add_patients() = to_proto(p);
    response->set_next_page_token(page.next_page_token);
    return ok_status();
  });
}

grpc::Status SoiqService::GetPatient(grpc::ServerContext* ctx, const v1::GetPatientRequest* request,
                                     v1::Patient* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(auto p, store_.get_patient(request->patient_id()));
    *response = to_proto(p);
    return ok_status();
  });
}

grpc::Status SoiqService::ListStudies(grpc::ServerContext* ctx, const v1::ListStudiesRequest* request,
                                      v1::ListStudiesResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(
        auto page, store_.list_studies(request->patient_id(), page_of(request->page_size(), request->page_token())));
    for (const auto& s : page.items) *response->add_studies() = to_proto(s);
    response->set_next_page_token(page.next_page_token);
    return ok_status();
  });
}

grpc::Status SoiqService::GetStudy(grpc::ServerContext* ctx, const v1::GetStudyRequest* request, v1::Study* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(auto s, store_.get_study(request->study_uid()));
    *response = to_proto(s);
    SOIQ_ASSIGN_OR_RETURN(auto series, store_.list_series(s.study_uid));
    for (const auto& r : series) *response->add_series() = to_proto(r);
    return ok_status();
  });
}

grpc::Status SoiqService::ListStructures(grpc::ServerContext* ctx, const v1::ListStructuresRequest* request,
                                         v1::ListStructuresResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_RETURN_IF_ERROR(check_laterality(request->laterality()).in_field("laterality"));
    db::StructureFilter f{request->patient_id(), request->study_uid(), request->name_glob(), request->laterality()};
    SOIQ_ASSIGN_OR_RETURN(auto page, store_.list_structures(f, page_of(request->page_size(), request->page_token())));
    for (const auto& s : page.items) *response->add_structures() = to_proto(s);
    response->set_next_page_token(page.next_page_token);
    return ok_status();
  });
}

grpc::Status SoiqService::GetStructure(grpc::ServerContext* ctx, const v1::GetStructureRequest* request,
                                       v1::Structure* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(auto s, store_.get_structure(request->id()));
    *response = to_proto(s);
    return ok_status();
  });
}

grpc::Status SoiqService::DownloadSurface(grpc::ServerContext* ctx, const v1::DownloadSurfaceRequest* request,
                                          grpc::ServerWriter<v1::DataChunk>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_RETURN_IF_ERROR(check_enum(request->coordinates(), v1::CoordinateSystem_IsValid, "coordinates"));
    SOIQ_ASSIGN_OR_RETURN(
        const std::string bytes,
        stored_surface_bytes(store_, features_, request->id(), request->format(), request->coordinates() == v1::RAS));
    for (size_t at = 0; at < bytes.size() || at == 0; at += kDownloadChunkBytes) {
      v1::DataChunk chunk;
      chunk.set_data(bytes.substr(at, kDownloadChunkBytes));
      if (at == 0) chunk.set_total_bytes(int64_t(bytes.size()));
      if (!writer->Write(chunk)) return Status(StatusCode::kCancelled, "the client closed the download");
      if (bytes.empty()) break;
    }
    return ok_status();
  });
}

grpc::Status SoiqService::DeleteStructure(grpc::ServerContext* ctx, const v1::DeleteStructureRequest* request,
                                          v1::DeleteResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(int64_t n, store_.delete_structure(request->id()));
    response->set_structures_deleted(n);
    return ok_status();
  });
}

grpc::Status SoiqService::DeletePatient(grpc::ServerContext* ctx, const v1::DeletePatientRequest* request,
                                        v1::DeleteResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(int64_t n, store_.delete_patient(request->patient_id()));
    response->set_structures_deleted(n);
    return ok_status();
  });
}

}  // namespace soiq::server
