#include "client/grpc_status.h"

#include <grpcpp/support/status.h>

#include <cstdio>

#include "soiq/v1/soiq.pb.h"

namespace soiq::client {

Status from_grpc_status(const grpc::Status& status, const std::string& address, std::chrono::milliseconds deadline,
                        bool answered_by_soiqd) {
  if (status.ok()) return ok_status();
  const auto code = static_cast<StatusCode>(static_cast<int>(status.error_code()));
  // An error about a field of the request: the field kept apart (Status::field), as soiqd sent it.
  if (soiq::v1::ErrorDetails details;
      !status.error_details().empty() && details.ParseFromString(status.error_details()) && !details.field().empty())
    return Status(code, details.reason()).in_field(details.field());
  std::string message = status.error_message();
  if (code == StatusCode::kUnavailable && !answered_by_soiqd) {
    message = "cannot reach soiqd at " + address + ": " + (message.empty() ? "unavailable" : message);
  } else if (code == StatusCode::kDeadlineExceeded && (message.empty() || message == "Deadline Exceeded")) {
    // gRPC's own text: the client gave up, the server said nothing.
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", double(deadline.count()) / 1000.0);
    message = "soiqd at " + address + " did not answer within the deadline (" + seconds +
              " s); raise it (soiq --timeout SECONDS) or narrow the request";
  } else if (message.empty()) {
    message = std::string(status_code_name(code)) + " from soiqd at " + address;
  }
  return Status(code, std::move(message));
}

}  // namespace soiq::client
