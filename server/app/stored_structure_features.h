#pragma once
// The features of one stored structure (the ComputeFeatures RPC): read from the feature cache when
// every asked value is there, otherwise computed on the worker pool (conversion included) and
// cached (server/app/feature_engine.h).
//
// Inputs   structure_id: a stored structure. ask: a completed FeatureAsk (complete_feature_ask).
// Output   The plan (grid, images, the wanted values in the order asked), every value by cache
//          entry, whether the cache answered, and how long the computation took (0 from the cache).
// Errors   NOT_FOUND for an unknown structure; FeatureEngine::plan's and compute's errors.

#include <cstdint>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/util/worker_pool.h"

namespace soiq::server {

struct StoredStructureFeatures {
  FeaturePlan plan;
  FeatureValues values;
  bool from_cache = false;
  double compute_ms = 0;
};

Result<StoredStructureFeatures> stored_structure_features(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                                          int64_t structure_id, const FeatureAsk& ask);

}  // namespace soiq::server
