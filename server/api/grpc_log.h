#pragma once
// gRPC's own log lines ("E1126 12:01:32.24 8488 chttp2_server.cc:1045] UNKNOWN:No address added
// ... {created_time: ...}") as soiqd's logfmt (server/util/log.h): one line, level and message,
// so that soiqd's stderr reads as one log and a failed start shows only soiqd's own reason.
//
// route_grpc_log()            installs the router, process-wide; call once, before any gRPC call.
// GrpcLogSilenced             while one lives, gRPC's lines are dropped (around a step whose failure
//                             soiqd reports itself, as binding the port).
// Thread-safety: the router and the silence flag may be used from any thread.

namespace soiq::server {

void route_grpc_log();

class GrpcLogSilenced {
 public:
  GrpcLogSilenced();
  ~GrpcLogSilenced();
  GrpcLogSilenced(const GrpcLogSilenced&) = delete;
  GrpcLogSilenced& operator=(const GrpcLogSilenced&) = delete;
};

}  // namespace soiq::server
