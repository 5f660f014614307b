#include "server/api/grpc_log.h"

#include <grpc/support/log.h>

#include <atomic>
#include <string>

#include "server/util/log.h"

namespace soiq::server {
namespace {

std::atomic<int> g_silenced{0};

void to_logfmt(gpr_log_func_args* args) {
  if (g_silenced.load() > 0 || args == nullptr || args->message == nullptr) return;
  std::string message = args->message;
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  const char* level = args->severity == GPR_LOG_SEVERITY_ERROR  ? "error"
                      : args->severity == GPR_LOG_SEVERITY_INFO ? "info"
                                                                : "debug";
  log_event(level, {{"event", "grpc"}, {"message", message}});
}

}  // namespace

void route_grpc_log() { gpr_set_log_function(to_logfmt); }

GrpcLogSilenced::GrpcLogSilenced() { ++g_silenced; }
GrpcLogSilenced::~GrpcLogSilenced() { --g_silenced; }

}  // namespace soiq::server
