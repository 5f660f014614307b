#pragma once
// soiq's one error model: a Status (canonical code + message) and a Result<T> (a value or a non-OK
// Status). Modelled on abseil's Status/StatusOr; codes carry gRPC's numbers so the server maps them
// once (server/api/grpc_status.cpp) and the CLI once (exit_code). No exception crosses a module.

#include <cassert>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace soiq {

enum class StatusCode : int {
  kOk = 0,
  kCancelled = 1,
  kUnknown = 2,
  kInvalidArgument = 3,
  kDeadlineExceeded = 4,
  kNotFound = 5,
  kAlreadyExists = 6,
  kPermissionDenied = 7,
  kResourceExhausted = 8,
  kFailedPrecondition = 9,
  kAborted = 10,
  kUnimplemented = 12,
  kInternal = 13,
  kUnavailable = 14,
  kDataLoss = 15,
  kUnauthenticated = 16,
};

// The canonical upper-case name, e.g. "INVALID_ARGUMENT".
const char* status_code_name(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;  // OK
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // "INVALID_ARGUMENT: mesh 'a.stl' has 3 NaN coordinates"
  std::string to_string() const;

  // The same error, about a field of a request: "stage1.min_age_years", "where[0]", "patient.sex".
  // The message gains the field in front ("where[0]: unknown feature ..."), so every reader sees
  // it, and field() and reason() keep the two apart, so that a client can say it in its own words
  // (the command line's "--where 'volume > 1'") without reading the prose. An error already about
  // a field nests under the new one: "where[0]" over "feature" is "where[0].feature".
  Status in_field(std::string_view field) const;
  const std::string& field() const { return field_; }
  // The message without the field in front: "unknown feature ...".
  std::string reason() const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
  std::string field_;  // "" unless in_field made this status
};

inline Status ok_status() { return Status(); }
inline Status invalid_argument(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status not_found(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
inline Status failed_precondition(std::string m) { return {StatusCode::kFailedPrecondition, std::move(m)}; }
inline Status resource_exhausted(std::string m) { return {StatusCode::kResourceExhausted, std::move(m)}; }
inline Status internal_error(std::string m) { return {StatusCode::kInternal, std::move(m)}; }
inline Status data_loss(std::string m) { return {StatusCode::kDataLoss, std::move(m)}; }
inline Status unimplemented(std::string m) { return {StatusCode::kUnimplemented, std::move(m)}; }

// A value or the non-OK Status that explains why there is none.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}         // NOLINT: implicit on purpose, like StatusOr
  Result(Status status) : status_(std::move(status)) {  // NOLINT
    assert(!status_.ok() && "a Result without a value needs a non-OK status");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }
  const T& value() const& {
    assert(ok());
    return *value_;
  }
  T& value() & {
    assert(ok());
    return *value_;
  }
  T&& value() && {
    assert(ok());
    return std::move(*value_);
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace soiq

// Early return of a non-OK Status from a function returning Status or Result<T>.
#define SOIQ_RETURN_IF_ERROR(expr)               \
  do {                                           \
    ::soiq::Status soiq_status_ = (expr);        \
    if (!soiq_status_.ok()) return soiq_status_; \
  } while (0)

#define SOIQ_CONCAT_INNER(a, b) a##b
#define SOIQ_CONCAT(a, b) SOIQ_CONCAT_INNER(a, b)
// `SOIQ_ASSIGN_OR_RETURN(auto mesh, read_mesh(path));`
#define SOIQ_ASSIGN_OR_RETURN(lhs, expr) SOIQ_ASSIGN_OR_RETURN_IMPL(SOIQ_CONCAT(soiq_result_, __LINE__), lhs, expr)
#define SOIQ_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                               \
  if (!tmp.ok()) return tmp.status();              \
  lhs = std::move(tmp).value()
