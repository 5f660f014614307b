#include "server/api/grpc_status.h"

#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

grpc::Status to_grpc(const Status& status) {
  if (status.ok()) return grpc::Status::OK;
  const auto code = static_cast<grpc::StatusCode>(static_cast<int>(status.code()));
  if (status.field().empty()) return grpc::Status(code, status.message());
  // The field apart from the prose (soiq.v1.ErrorDetails), for clients to name in their own words.
  v1::ErrorDetails details;
  details.set_code(int(status.code()));
  details.set_message(status.message());
  details.set_field(status.field());
  details.set_reason(status.reason());
  return grpc::Status(code, status.message(), details.SerializeAsString());
}

}  // namespace soiq::server
