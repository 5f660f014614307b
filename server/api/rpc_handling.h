#pragma once
// What every SoiqService handler shares (server/api/soiq_service*.cpp): the call wrapper that
// authorizes, logs one logfmt line and maps the one error model to gRPC once, and the hand-off of
// heavy work to the worker pool. Included only by the service's own .cpp files.

#include <chrono>
#include <cstdio>
#include <future>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "server/api/grpc_status.h"
#include "server/api/soiq_service.h"
#include "server/util/log.h"

namespace soiq::server {

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

inline void log_rpc(const char* method, const Status& status, double ms) {
  char t[32];
  std::snprintf(t, sizeof t, "%.1f", ms);
  std::vector<std::pair<std::string, std::string>> fields = {
      {"event", "rpc"}, {"method", method}, {"code", status_code_name(status.code())}, {"ms", t}};
  if (!status.ok()) fields.emplace_back("error", status.message());
  log_event(status.ok() ? "info" : "warn", fields);
}

// Why a call should stop, for work that polls (MemoryBudget::reserve while it waits, queries):
// OK while the client still waits for the answer.
inline Status stop_status(const grpc::ServerContext& ctx) {
  if (!ctx.IsCancelled()) return ok_status();
  if (ctx.deadline() <= std::chrono::system_clock::now())
    return Status(StatusCode::kDeadlineExceeded, "the request ran past its deadline and was stopped");
  return Status(StatusCode::kCancelled, "the request was cancelled by the client");
}

template <typename Body>
grpc::Status SoiqService::handle(const char* method, grpc::ServerContext& ctx, Body&& body) {
  const Clock::time_point start = Clock::now();
  Status status = authorize(ctx);
  if (status.ok()) status = body();
  log_rpc(method, status, ms_since(start));
  // Tells the client that soiqd itself answered: an UNAVAILABLE from here is the PACS's, not ours.
  if (!status.ok()) ctx.AddTrailingMetadata("soiq-origin", "soiqd");
  return to_grpc(status);
}

template <typename T>
Result<T> SoiqService::on_pool(const std::function<Result<T>()>& work) {
  return pool_.call(work);
}

}  // namespace soiq::server
