#pragma once
// The client's one adapter from gRPC's status to soiq's (STYLE.md section 3: map once on each
// side; the server's counterpart is server/api/grpc_status.cpp).
//
// The code keeps its number (soiq::StatusCode uses gRPC's). The server's message is kept as it is,
// except where gRPC itself wrote it and a person needs to know what to do:
//   UNAVAILABLE        "cannot reach soiqd at ADDRESS: <gRPC's text>" when soiqd did not answer
//                      (`answered_by_soiqd` false: no "soiq-origin" trailer came back). When soiqd
//                      answered UNAVAILABLE itself (its PACS is down), its message is kept: the
//                      failure is the PACS's, and blaming soiqd would send people the wrong way.
//   DEADLINE_EXCEEDED  "soiqd at ADDRESS did not answer within the deadline (Ns); ..." when the
//                      message is gRPC's own "Deadline Exceeded"
// An error soiqd sent about a field of the request (soiq.v1.ErrorDetails in the status details)
// comes back with Status::field() set, so a command can name its option instead.
// Cost: O(message length); thread-safe.

#include <chrono>
#include <string>

#include "core/base/status.h"

namespace grpc {
class Status;
}

namespace soiq::client {

Status from_grpc_status(const grpc::Status& status, const std::string& address, std::chrono::milliseconds deadline,
                        bool answered_by_soiqd = false);

// The trailing-metadata key soiqd sets on every error it returns itself.
inline constexpr const char* kSoiqOriginKey = "soiq-origin";

}  // namespace soiq::client
