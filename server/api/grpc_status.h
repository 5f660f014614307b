#pragma once
// The one place where soiq's Status becomes a gRPC status (the codes share gRPC's numbers, so the
// mapping keeps code and message; STYLE.md: map errors once, at the edge). An error about a field
// (Status::field) also carries soiq.v1.ErrorDetails in the status details.

#include <grpcpp/support/status.h>

#include "core/base/status.h"

namespace soiq::server {

grpc::Status to_grpc(const Status& status);

}  // namespace soiq::server
