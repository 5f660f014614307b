#include "client/cli/exit_code.h"

namespace soiq::cli {

int exit_code(const soiq::Status& status) {
  switch (status.code()) {
    case StatusCode::kOk:
      return 0;
    case StatusCode::kInvalidArgument:
      return 2;
    case StatusCode::kNotFound:
      return 3;
    case StatusCode::kAlreadyExists:
    case StatusCode::kFailedPrecondition:
      return 4;
    case StatusCode::kResourceExhausted:
      return 5;
    case StatusCode::kUnavailable:
    case StatusCode::kDeadlineExceeded:
    case StatusCode::kCancelled:
      return 6;
    case StatusCode::kUnauthenticated:
    case StatusCode::kPermissionDenied:
      return 7;
    default:
      return 1;
  }
}

}  // namespace soiq::cli
