// SoiqService's construction, its one authorization check and GetServerInfo. The handlers live by
// kind: soiq_service_uploads.cpp, _records.cpp, _compute.cpp and _dicom.cpp.
#include "server/api/soiq_service.h"

#include <openssl/crypto.h>

#include "core/features/feature_catalogue.h"
#include "db/validate_records.h"
#include "server/api/proto_records.h"
#include "server/api/rpc_handling.h"

namespace soiq::server {

SoiqService::SoiqService(db::Store& store, const ServerConfig& config, std::string token)
    : store_(store),
      config_(config),
      token_(std::move(token)),
      budget_(config.memory_budget_bytes, decoded_cache_share(config.memory_budget_bytes)),
      features_(store, config.max_grid_voxels, budget_, budget_.cache_bytes()),
      pool_(config.workers),
      sharing_(config.share_stage2
                   ? std::make_unique<SharedStage2>(
                         store, features_, pool_,
                         SharingOptions{config.replica_id, std::chrono::milliseconds(config.replica_live_ms)})
                   : nullptr),
      queries_(store, features_, pool_, QueryLimits{config.query_result_cap, config.stage1_cap}, sharing_.get()),
      precompute_(store, features_,
                  config.precompute_weighted ? db::PrecomputedSet::kWithWeighted : db::PrecomputedSet::kDefault,
                  [this] { return !sharing_ || sharing_->leads(); }) {}

Status SoiqService::start_background_work() {
  if (sharing_) SOIQ_RETURN_IF_ERROR(sharing_->start());
  if (!config_.precompute) return ok_status();
  return precompute_.start();
}

void SoiqService::queued_work() {
  if (config_.precompute) precompute_.notify();
}

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

grpc::Status SoiqService::GetServerInfo(grpc::ServerContext* ctx, const v1::GetServerInfoRequest*,
                                        v1::ServerInfo* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(db::Counts c, store_.counts());
    response->set_version(SOIQ_VERSION);
    response->set_feature_definition_version(feature_definitions_version());
    for (const FeatureDef& f : feature_catalogue()) *response->add_features() = to_proto(f);
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
    for (const std::string& m : c.series_modalities) response->add_series_modalities(m);
    response->set_precompute_queued(c.precompute_queued);
    response->set_precompute_failed(c.precompute_failed);
    response->set_precompute_enabled(config_.precompute);
    response->set_instances(c.instances);
    response->set_instance_files(c.instance_files);
    response->set_instance_bytes(c.instance_bytes);
    response->set_keep_instances(config_.keep_instances);
    if (config_.pacs_peer) response->set_pacs(dicom::describe_pacs_peer(*config_.pacs_peer));
    return ok_status();
  });
}

}  // namespace soiq::server
