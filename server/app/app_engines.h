#pragma once
// The engines soiqd's front ends share, borrowed: the gRPC service (server/api/) owns them, and
// DICOMweb (server/http/) uses the same ones, so both see one memory budget, one worker pool
// (--workers bounds conversions from either) and one feature cache.

#include <functional>

#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/app/memory_budget.h"
#include "server/app/query_engine.h"
#include "server/app/server_config.h"
#include "server/util/worker_pool.h"

namespace soiq::server {

struct AppEngines {
  db::Store& store;
  const ServerConfig& config;
  MemoryBudget& budget;
  FeatureEngine& features;
  WorkerPool& pool;
  QueryEngine& queries;
  // To call after a write that queued structures for precompute (wakes the worker).
  std::function<void()> queued_work;
};

}  // namespace soiq::server
