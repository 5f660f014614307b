#include "server/http/http_status.h"

#include <nlohmann/json.hpp>

namespace soiq::server::http {

int http_status_of(StatusCode code) {
  switch (code) {
    case StatusCode::kOk:
      return 200;
    case StatusCode::kInvalidArgument:
      return 400;
    case StatusCode::kUnauthenticated:
      return 401;
    case StatusCode::kPermissionDenied:
      return 403;
    case StatusCode::kNotFound:
      return 404;
    case StatusCode::kFailedPrecondition:
    case StatusCode::kAlreadyExists:
    case StatusCode::kAborted:
      return 409;
    case StatusCode::kResourceExhausted:
      return 413;
    case StatusCode::kUnimplemented:
      return 501;
    case StatusCode::kUnavailable:
    case StatusCode::kCancelled:
      return 503;
    case StatusCode::kDeadlineExceeded:
      return 504;
    default:
      return 500;
  }
}

std::string error_body(const Status& s) { return error_body(s, http_status_of(s.code())); }

std::string error_body(const Status& s, int http_status) {
  nlohmann::json body = {
      {"error", {{"code", status_code_name(s.code())}, {"status", http_status}, {"message", s.message()}}}};
  // The request field the error is about, apart from the prose, as gRPC's ErrorDetails carries it.
  if (!s.field().empty()) {
    body["error"]["field"] = s.field();
    body["error"]["reason"] = s.reason();
  }
  return body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace soiq::server::http
