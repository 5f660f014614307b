#pragma once
// The client's one adapter from gRPC's status to soiq's (STYLE.md section 3: map once on each
// side; the server's counterpart is server/grpc_status.cpp).
//
// The code keeps its number (soiq::StatusCode uses gRPC's). The server's message is kept as it is,
// except where gRPC itself wrote it and a person needs to know what to do:
//   UNAVAILABLE        "cannot reach soiqd at ADDRESS: <gRPC's text>"
//   DEADLINE_EXCEEDED  "soiqd at ADDRESS did not answer within the deadline (Ns); ..." when the
//                      message is gRPC's own "Deadline Exceeded"
// Cost: O(message length); thread-safe.

#include <chrono>
#include <string>

#include "core/status.h"

namespace grpc {
class Status;
}

namespace soiq::client {

Status from_grpc_status(const grpc::Status& status, const std::string& address, std::chrono::milliseconds deadline);

}  // namespace soiq::client
