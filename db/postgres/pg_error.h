#pragma once
// A PostgreSQL failure as soiq's Status, by its SQLSTATE (PostgreSQL's documentation, Appendix A
// "PostgreSQL Error Codes"), so the server maps it to gRPC once like any other store error:
//   40001 serialization_failure, 40P01 deadlock_detected  ABORTED (retryable: pg_transaction retries)
//   08xxx connection exceptions, 57P01-57P03 shutdown     UNAVAILABLE
//   23505 unique_violation                                ALREADY_EXISTS
//   23xxx other integrity violations                      FAILED_PRECONDITION
//   22xxx data exceptions (text not UTF-8, out of range)  INVALID_ARGUMENT
//   53xxx insufficient resources (disk full, memory)      RESOURCE_EXHAUSTED
//   28xxx authentication                                  UNAUTHENTICATED
//   42501 insufficient_privilege                          PERMISSION_DENIED
//   XX001, XX002 data or index corrupted                  DATA_LOSS
//   anything else                                         INTERNAL
// The message keeps `what` (the caller's words), the server's message and the SQLSTATE.

#include <string>
#include <string_view>

#include "core/base/status.h"

namespace soiq::db {

Status pg_status(std::string_view sqlstate, std::string_view server_message, std::string_view what);

// Whether a transaction that failed with `s` may succeed when run again.
bool pg_retryable(const Status& s);

}  // namespace soiq::db
