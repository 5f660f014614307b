#pragma once
// The gRPC service: thin handlers (STYLE.md) that check the token, turn messages into the store's
// records or the engines' asks, call them, and map the one error model to gRPC once (to_grpc).
// Limits: uploads larger than max_upload_bytes are RESOURCE_EXHAUSTED as soon as the stream passes
// the limit (nothing stored); grids larger than max_grid_voxels likewise, before allocation.

#include <functional>
#include <memory>
#include <string>

#include "db/store.h"
#include "server/app/app_engines.h"
#include "server/app/feature_engine.h"
#include "server/app/memory_budget.h"
#include "server/app/precompute_worker.h"
#include "server/app/query_engine.h"
#include "server/app/server_config.h"
#include "server/util/worker_pool.h"
#include "soiq/v1/soiq.grpc.pb.h"

namespace soiq::server {

class SoiqService final : public v1::Soiq::Service {
 public:
  // `token` empty: no authentication.
  SoiqService(db::Store& store, const ServerConfig& config, std::string token);
  // Starts precompute (unless --precompute off): call once, before serving.
  Status start_background_work();
  // The engines, for soiqd's other front end (DICOMweb); valid while the service lives.
  AppEngines engines() {
    return {store_, config_, budget_, features_, pool_, queries_, [this] { queued_work(); }};
  }

  grpc::Status UploadSurface(grpc::ServerContext* ctx, grpc::ServerReader<v1::UploadSurfaceRequest>* reader,
                             v1::UploadSurfaceResponse* response) override;
  grpc::Status UploadImage(grpc::ServerContext* ctx, grpc::ServerReader<v1::UploadImageRequest>* reader,
                           v1::UploadImageResponse* response) override;
  grpc::Status ImportDicom(grpc::ServerContext* ctx, grpc::ServerReader<v1::ImportDicomRequest>* reader,
                           v1::ImportDicomResponse* response) override;
  grpc::Status ListPatients(grpc::ServerContext* ctx, const v1::ListPatientsRequest* request,
                            v1::ListPatientsResponse* response) override;
  grpc::Status GetPatient(grpc::ServerContext* ctx, const v1::GetPatientRequest* request,
                          v1::Patient* response) override;
  grpc::Status ListStudies(grpc::ServerContext* ctx, const v1::ListStudiesRequest* request,
                           v1::ListStudiesResponse* response) override;
  grpc::Status GetStudy(grpc::ServerContext* ctx, const v1::GetStudyRequest* request, v1::Study* response) override;
  grpc::Status ListStructures(grpc::ServerContext* ctx, const v1::ListStructuresRequest* request,
                              v1::ListStructuresResponse* response) override;
  grpc::Status GetStructure(grpc::ServerContext* ctx, const v1::GetStructureRequest* request,
                            v1::Structure* response) override;
  grpc::Status DownloadSurface(grpc::ServerContext* ctx, const v1::DownloadSurfaceRequest* request,
                               grpc::ServerWriter<v1::DataChunk>* writer) override;
  grpc::Status DeleteStructure(grpc::ServerContext* ctx, const v1::DeleteStructureRequest* request,
                               v1::DeleteResponse* response) override;
  grpc::Status DeletePatient(grpc::ServerContext* ctx, const v1::DeletePatientRequest* request,
                             v1::DeleteResponse* response) override;
  grpc::Status Convert(grpc::ServerContext* ctx, const v1::ConvertRequest* request,
                       grpc::ServerWriter<v1::ConvertResponse>* writer) override;
  grpc::Status ComputeFeatures(grpc::ServerContext* ctx, const v1::FeaturesRequest* request,
                               v1::FeaturesResponse* response) override;
  grpc::Status Query(grpc::ServerContext* ctx, const v1::QueryRequest* request,
                     grpc::ServerWriter<v1::QueryEvent>* writer) override;
  grpc::Status GetServerInfo(grpc::ServerContext* ctx, const v1::GetServerInfoRequest* request,
                             v1::ServerInfo* response) override;
  // DICOM SEG and RT Structure Set export and the PACS (server/api/soiq_service_dicom.cpp).
  grpc::Status Render(grpc::ServerContext* ctx, const v1::RenderRequest* request,
                      grpc::ServerWriter<v1::RenderResponse>* writer) override;
  grpc::Status ExportSeg(grpc::ServerContext* ctx, const v1::ExportSegRequest* request,
                         grpc::ServerWriter<v1::ExportSegResponse>* writer) override;
  grpc::Status ExportRtStruct(grpc::ServerContext* ctx, const v1::ExportRtStructRequest* request,
                              grpc::ServerWriter<v1::ExportRtStructResponse>* writer) override;
  grpc::Status PacsEcho(grpc::ServerContext* ctx, const v1::PacsEchoRequest* request,
                        v1::PacsEchoResponse* response) override;
  grpc::Status PacsFind(grpc::ServerContext* ctx, const v1::PacsFindRequest* request,
                        v1::PacsFindResponse* response) override;
  grpc::Status PacsPull(grpc::ServerContext* ctx, const v1::PacsPullRequest* request,
                        grpc::ServerWriter<v1::PacsPullEvent>* writer) override;
  grpc::Status PacsPush(grpc::ServerContext* ctx, const v1::PacsPushRequest* request,
                        v1::PacsPushResponse* response) override;

 private:
  Status authorize(const grpc::ServerContext& ctx) const;
  // After a write that queued structures for precompute.
  void queued_work();
  // The configured PACS, or FAILED_PRECONDITION naming --pacs.
  Result<dicom::PacsPeer> pacs() const;
  // Every handler: authorize, run `body` (returns soiq::Status), log, and map once to gRPC.
  // Runs `work` on the worker pool and waits: conversions and features from every RPC share the
  // pool, so --workers bounds how many run at once.
  template <typename T>
  Result<T> on_pool(const std::function<Result<T>()>& work);
  template <typename Body>
  grpc::Status handle(const char* method, grpc::ServerContext& ctx, Body&& body);

  db::Store& store_;
  const ServerConfig config_;
  const std::string token_;
  MemoryBudget budget_;  // before features_, which admits work against it
  FeatureEngine features_;
  WorkerPool pool_;  // after features_: destroyed (joined) first
  // With other replicas on a shared database: after pool_, whose workers run its items (so it is
  // stopped before the pool), before queries_, which posts to it.
  std::unique_ptr<SharedStage2> sharing_;
  QueryEngine queries_;
  PrecomputeWorker precompute_;  // last: stopped first, before what it uses
};

}  // namespace soiq::server
