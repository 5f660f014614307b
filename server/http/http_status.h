#pragma once
// The one mapping of soiq's Status to HTTP (as server/api/grpc_status.h is to gRPC): the status
// code and the JSON error body every DICOMweb and /soiq/v1 error carries,
//   {"error": {"code": "INVALID_ARGUMENT", "status": 400, "message": "..."}},
// with "field" and "reason" besides when the error is about one field of a request (Status::field).
//
//   INVALID_ARGUMENT -> 400                    NOT_FOUND -> 404
//   UNAUTHENTICATED -> 401                     PERMISSION_DENIED -> 403
//   FAILED_PRECONDITION, ALREADY_EXISTS,       RESOURCE_EXHAUSTED -> 413 (a size, count or memory
//     ABORTED -> 409 (PS3.18: a conflict         limit; the message names it)
//     with what is stored)                     UNIMPLEMENTED -> 501
//   UNAVAILABLE, CANCELLED -> 503              DEADLINE_EXCEEDED -> 504
//   DATA_LOSS, INTERNAL, UNKNOWN -> 500

#include <string>

#include "core/base/status.h"

namespace soiq::server::http {

int http_status_of(StatusCode code);
std::string error_body(const Status& s);
// The same body for an HTTP status no Status code maps to (406, 415).
std::string error_body(const Status& s, int http_status);

}  // namespace soiq::server::http
