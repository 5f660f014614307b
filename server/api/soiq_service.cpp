#include "server/api/soiq_service.h"

#include <openssl/crypto.h>

#include <chrono>
#include <optional>

#include "core/base/run_length_volume.h"
#include "core/features/feature_catalogue.h"
#include "core/features/structure_features.h"
#include "core/io/write_image.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"
#include "db/validate_records.h"
#include "server/api/grpc_status.h"
#include "server/api/proto_records.h"
#include "server/api/received_dicom_files.h"
#include "server/api/rpc_handling.h"
#include "server/app/dicom_import.h"
#include "server/app/uploaded_files.h"
#include "server/util/log.h"
#include "server/util/temp_dir.h"
#include "server/util/temp_file.h"

namespace soiq::server {
namespace {

constexpr size_t kChunkBytes = 1 << 20;  // download chunks: well under gRPC's 4 MiB message limit

db::PageRequest page_of(int32_t size, const std::string& token) {
  db::PageRequest p;
  p.page_size = size <= 0 ? 100 : std::min(size, 1000);
  p.page_token = token;
  return p;
}

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

Result<std::vector<db::SeriesRecord>> series_of(db::Store& store, const std::string& study_uid) {
  return store.list_series(study_uid);
}

FillRule fill_rule_of(v1::FillRule f) { return f == v1::EVEN_ODD ? FillRule::kEvenOdd : FillRule::kNonZero; }

}  // namespace

SoiqService::SoiqService(db::Store& store, const ServerConfig& config, std::string token)
    : store_(store),
      config_(config),
      token_(std::move(token)),
      budget_(config.memory_budget_bytes),
      features_(store, config.max_grid_voxels, budget_),
      pool_(config.workers),
      queries_(store, features_, pool_, QueryLimits{config.query_result_cap, config.stage1_cap}) {}

Status SoiqService::authorize(const grpc::ServerContext& ctx) const {
  if (token_.empty()) return ok_status();
  const auto& md = ctx.client_metadata();
  auto it = md.find("authorization");
  if (it == md.end())
    return Status(StatusCode::kUnauthenticated, "this server needs a bearer token: pass --token-file FILE");
  const std::string given(it->second.data(), it->second.size());
  const std::string expected = "Bearer " + token_;
  // Constant time: a wrong token must not leak how much of it was right.
  if (given.size() != expected.size() || CRYPTO_memcmp(given.data(), expected.data(), given.size()) != 0)
    return Status(StatusCode::kUnauthenticated, "the bearer token is not valid for this server");
  return ok_status();
}

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
    SOIQ_ASSIGN_OR_RETURN(db::AddedStructure added, store_.add_structure(s));
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

grpc::Status SoiqService::ListPatients(grpc::ServerContext* ctx, const v1::ListPatientsRequest* request,
                                       v1::ListPatientsResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_RETURN_IF_ERROR(check_sex(request->sex(), "sex"));
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
    SOIQ_ASSIGN_OR_RETURN(auto series, series_of(store_, s.study_uid));
    for (const auto& r : series) *response->add_series() = to_proto(r);
    return ok_status();
  });
}

grpc::Status SoiqService::ListStructures(grpc::ServerContext* ctx, const v1::ListStructuresRequest* request,
                                         v1::ListStructuresResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_RETURN_IF_ERROR(check_laterality(request->laterality()));
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
    SOIQ_ASSIGN_OR_RETURN(auto s, store_.get_structure(request->id()));
    SOIQ_ASSIGN_OR_RETURN(auto mesh, features_.surface(s.surface.sha256));
    SOIQ_ASSIGN_OR_RETURN(std::string bytes,
                          surface_bytes(*mesh, request->format(), request->coordinates() == v1::RAS));
    for (size_t at = 0; at < bytes.size() || at == 0; at += kChunkBytes) {
      v1::DataChunk chunk;
      chunk.set_data(bytes.substr(at, kChunkBytes));
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

grpc::Status SoiqService::Convert(grpc::ServerContext* ctx, const v1::ConvertRequest* request,
                                  grpc::ServerWriter<v1::ConvertResponse>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    const Clock::time_point start = Clock::now();
    SOIQ_RETURN_IF_ERROR(check_enum(request->fill_rule(), v1::FillRule_IsValid, "fill_rule"));
    SOIQ_RETURN_IF_ERROR(check_enum(request->encoding(), v1::VolumeEncoding_IsValid, "encoding"));
    SOIQ_ASSIGN_OR_RETURN(auto s, store_.get_structure(request->structure_id()));
    SOIQ_ASSIGN_OR_RETURN(GridChoice choice, grid_choice(request->grid()));
    SOIQ_ASSIGN_OR_RETURN(auto series, series_of(store_, s.study_uid));
    SOIQ_ASSIGN_OR_RETURN(ResolvedGrid grid, resolve_grid(choice, s, series, 0, config_.max_grid_voxels));
    // Admitted on the worker, never before: a reservation held while waiting for a worker could
    // block workers that wait for the budget. Held until the last chunk is sent: the runs (and
    // the mask) live that long.
    FeatureEngine::WorkExtras extras;
    extras.mask_export = request->encoding() != v1::RUNS;
    struct Admitted {
      MemoryBudget::Reservation held;
      Voxelization v;
    };
    SOIQ_ASSIGN_OR_RETURN(
        Admitted admitted, on_pool<Admitted>([&]() -> Result<Admitted> {
          SOIQ_ASSIGN_OR_RETURN(MemoryBudget::Reservation held,
                                features_.admit(s, grid.geometry, extras, [&] { return stop_status(*ctx); }));
          SOIQ_ASSIGN_OR_RETURN(Voxelization v,
                                features_.convert(s, grid.geometry, fill_rule_of(request->fill_rule())));
          return Admitted{std::move(held), std::move(v)};
        }));
    const Voxelization& v = admitted.v;
    v1::ConvertResponse first;
    v1::ConvertSummary* summary = first.mutable_summary();
    *summary->mutable_geometry() = to_proto(grid.geometry);
    summary->set_voxel_count(voxel_count(v.volume));
    summary->set_volume_mm3(double(summary->voxel_count()) * grid.geometry.voxel_volume_mm3());
    summary->set_milliseconds(ms_since(start));
    summary->set_defects(s.robust ? describe(v.defects) : "closed (checked at upload)");
    if (!writer->Write(first)) return Status(StatusCode::kCancelled, "the client closed the conversion");
    if (request->encoding() == v1::RUNS) {
      v1::ConvertResponse batch;
      const int64_t nlines = v.volume.line_count(), ny = grid.geometry.dims[1];
      for (int64_t l = 0; l < nlines; ++l) {
        for (int64_t r = v.volume.line_start[l]; r < v.volume.line_start[l + 1]; ++r) {
          v1::RunBatch* b = batch.mutable_runs();
          b->add_j(int32_t(l % ny));
          b->add_k(int32_t(l / ny));
          b->add_begin(v.volume.runs[r].begin);
          b->add_end(v.volume.runs[r].end);
          if (b->j_size() == 65536) {
            if (!writer->Write(batch)) return Status(StatusCode::kCancelled, "the client closed the conversion");
            batch.Clear();
          }
        }
      }
      if (batch.has_runs() && !writer->Write(batch))
        return Status(StatusCode::kCancelled, "the client closed the conversion");
      return ok_status();
    }
    SOIQ_ASSIGN_OR_RETURN(Mask mask, to_mask(v.volume, config_.max_grid_voxels));
    SOIQ_ASSIGN_OR_RETURN(TempFile file, TempFile::create(".nii.gz"));
    SOIQ_RETURN_IF_ERROR(write_mask(mask, file.path()));
    SOIQ_ASSIGN_OR_RETURN(std::string bytes, file.read());
    for (size_t at = 0; at < bytes.size(); at += kChunkBytes) {
      v1::ConvertResponse chunk;
      chunk.set_nifti_chunk(bytes.substr(at, kChunkBytes));
      if (!writer->Write(chunk)) return Status(StatusCode::kCancelled, "the client closed the conversion");
    }
    return ok_status();
  });
}

grpc::Status SoiqService::ComputeFeatures(grpc::ServerContext* ctx, const v1::FeaturesRequest* request,
                                          v1::FeaturesResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(auto s, store_.get_structure(request->structure_id()));
    FeatureAsk ask;
    ask.names.assign(request->features().begin(), request->features().end());
    for (const std::string& r : request->regions()) {
      SOIQ_ASSIGN_OR_RETURN(RegionSpec spec, parse_region(r));
      ask.regions.push_back(spec);
    }
    ask.images.assign(request->images().begin(), request->images().end());
    if (request->images_size() > 0 && request->features_size() == 0) {
      // Images without names: every shape and intensity feature.
      ask.names = shape_feature_names();
      for (const auto& n : intensity_feature_names())
        if (std::find(ask.names.begin(), ask.names.end(), n) == ask.names.end()) ask.names.push_back(n);
    }
    SOIQ_RETURN_IF_ERROR(check_enum(request->interpolation(), v1::Interpolation_IsValid, "interpolation"));
    ask.interpolation = request->interpolation() == v1::LINEAR ? Interpolation::kLinear : Interpolation::kNearest;
    SOIQ_ASSIGN_OR_RETURN(ask.grid, grid_choice(request->grid()));
    SOIQ_RETURN_IF_ERROR(complete_feature_ask(ask));
    SOIQ_ASSIGN_OR_RETURN(auto series, series_of(store_, s.study_uid));
    SOIQ_ASSIGN_OR_RETURN(FeaturePlan plan, features_.plan(s, series, ask));
    SOIQ_ASSIGN_OR_RETURN(std::vector<db::CachedFeature> cached, store_.cached_features({plan.cache_key}));
    FeatureValues values;
    for (auto& c : cached) values[c.entry] = std::move(c.value);
    const bool hit = std::all_of(plan.wants.begin(), plan.wants.end(),
                                 [&](const WantedValue& w) { return values.count(w.entry) > 0; });
    const Clock::time_point start = Clock::now();
    if (!hit) {
      SOIQ_ASSIGN_OR_RETURN(values, on_pool<FeatureValues>([&] { return features_.compute(plan, ask); }));
      v1::Timing* t = response->add_timings();
      t->set_part("conversion and features");
      t->set_milliseconds(ms_since(start));
    }
    response->set_from_cache(hit);
    *response->mutable_geometry() = to_proto(plan.grid.geometry);
    for (const WantedValue& w : plan.wants) {
      v1::FeatureValue* f = response->add_features();
      f->set_name(w.name);
      f->set_region(w.region);
      f->set_image(w.image);
      for (double x : values.at(w.entry)) f->add_value(x);
    }
    return ok_status();
  });
}

grpc::Status SoiqService::Query(grpc::ServerContext* ctx, const v1::QueryRequest* request,
                                grpc::ServerWriter<v1::QueryEvent>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    return queries_.run(
        *request, [&] { return stop_status(*ctx); }, [&](const v1::QueryEvent& e) { return writer->Write(e); });
  });
}

grpc::Status SoiqService::GetServerInfo(grpc::ServerContext* ctx, const v1::GetServerInfoRequest*,
                                        v1::ServerInfo* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(db::Counts c, store_.counts());
    response->set_version(SOIQ_VERSION);
    response->set_feature_definition_version(feature_definitions_version());
    for (const FeatureDef& f : feature_catalogue()) {
      v1::FeatureInfo* info = response->add_features();
      info->set_name(std::string(f.name));
      info->set_family(std::string(family_name(f.family)));
      info->set_unit(std::string(f.unit));
      info->set_needs(std::string(feature_needs(f)));
      info->set_summary(std::string(f.summary));
      info->set_version(f.version);
      info->set_components(f.components);
    }
    response->set_max_upload_bytes(config_.max_upload_bytes);
    response->set_max_grid_voxels(config_.max_grid_voxels);
    response->set_max_concurrent_conversions(config_.workers);
    response->set_memory_budget_bytes(budget_.limit());
    response->set_memory_in_use_bytes(budget_.in_use());
    response->set_memory_peak_bytes(budget_.peak());
    response->set_query_result_cap(config_.query_result_cap);
    response->set_stage1_cap(config_.stage1_cap);
    response->set_max_id_bytes(int32_t(db::kMaxIdBytes));
    response->set_max_name_bytes(int32_t(db::kMaxNameBytes));
    response->set_patients(c.patients);
    response->set_studies(c.studies);
    response->set_structures(c.structures);
    response->set_surfaces(c.surfaces);
    response->set_series(c.series);
    response->set_cached_features(c.cached_features);
    if (config_.pacs_peer) response->set_pacs(dicom::describe_pacs_peer(*config_.pacs_peer));
    return ok_status();
  });
}

}  // namespace soiq::server
