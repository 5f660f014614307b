#pragma once
// The one place where soiq's Status becomes a gRPC status (the codes share gRPC's numbers, so the
// mapping keeps code and message; STYLE.md: map errors once, at the edge).

#include <grpcpp/support/status.h>

#include "core/base/status.h"

namespace soiq::server {

grpc::Status to_grpc(const Status& status);

}  // namespace soiq::server
