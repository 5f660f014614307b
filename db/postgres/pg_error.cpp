#include "db/postgres/pg_error.h"

namespace soiq::db {

Status pg_status(std::string_view sqlstate, std::string_view server_message, std::string_view what) {
  std::string message(what);
  message += ": ";
  message += server_message;
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  if (!sqlstate.empty()) message += " (SQLSTATE " + std::string(sqlstate) + ")";
  auto starts = [&](std::string_view prefix) { return sqlstate.substr(0, prefix.size()) == prefix; };
  if (sqlstate == "40001" || sqlstate == "40P01") return {StatusCode::kAborted, message + "; retry"};
  if (starts("08") || sqlstate == "57P01" || sqlstate == "57P02" || sqlstate == "57P03" || sqlstate.empty())
    return {StatusCode::kUnavailable, message};
  if (sqlstate == "23505") return {StatusCode::kAlreadyExists, message};
  if (starts("23")) return failed_precondition(message);
  // Data exceptions: text that is not UTF-8 (22021), a value out of a column's range (22003), ...
  // the input's fault, as a bad value is everywhere else.
  if (starts("22")) return invalid_argument(message);
  if (starts("53")) return resource_exhausted(message);
  if (starts("28")) return {StatusCode::kUnauthenticated, message};
  if (sqlstate == "42501") return {StatusCode::kPermissionDenied, message};
  if (sqlstate == "XX001" || sqlstate == "XX002") return data_loss(message);
  return internal_error(message);
}

bool pg_retryable(const Status& s) { return s.code() == StatusCode::kAborted; }

}  // namespace soiq::db
