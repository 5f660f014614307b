"""soiq's errors in Python: one exception class per gRPC status code soiqd answers with.

soiqd maps every failure to a canonical gRPC code with a message a person can act on
(proto/soiq/v1/soiq.proto); the client raises the matching subclass of SoiqError, so a caller
can catch NotFound or InvalidArgument without looking at codes.
"""

import grpc


class SoiqError(Exception):
    """A call soiqd refused or could not answer. `code` is the grpc.StatusCode; `field` the request
    field the error is about ("stage1.min_age_years", "where[0]") when soiqd named one, else ""."""

    code = grpc.StatusCode.UNKNOWN

    def __init__(self, message, code=None, field=""):
        super().__init__(message)
        self.message = message
        self.field = field
        if code is not None:
            self.code = code


class InvalidArgument(SoiqError):
    code = grpc.StatusCode.INVALID_ARGUMENT


class NotFound(SoiqError):
    code = grpc.StatusCode.NOT_FOUND


class AlreadyExists(SoiqError):
    code = grpc.StatusCode.ALREADY_EXISTS


class FailedPrecondition(SoiqError):
    code = grpc.StatusCode.FAILED_PRECONDITION


class ResourceExhausted(SoiqError):
    code = grpc.StatusCode.RESOURCE_EXHAUSTED


class Unauthenticated(SoiqError):
    code = grpc.StatusCode.UNAUTHENTICATED


class PermissionDenied(SoiqError):
    code = grpc.StatusCode.PERMISSION_DENIED


class Unavailable(SoiqError):
    code = grpc.StatusCode.UNAVAILABLE


class DeadlineExceeded(SoiqError):
    code = grpc.StatusCode.DEADLINE_EXCEEDED


class Cancelled(SoiqError):
    code = grpc.StatusCode.CANCELLED


class DataLoss(SoiqError):
    code = grpc.StatusCode.DATA_LOSS


class Internal(SoiqError):
    code = grpc.StatusCode.INTERNAL


_BY_CODE = {c.code: c for c in (InvalidArgument, NotFound, AlreadyExists, FailedPrecondition, ResourceExhausted,
                                 Unauthenticated, PermissionDenied, Unavailable, DeadlineExceeded, Cancelled,
                                 DataLoss, Internal)}


def from_rpc_error(error):
    """The SoiqError for a grpc.RpcError (a call's failure as gRPC raised it)."""
    code = error.code() if hasattr(error, "code") else grpc.StatusCode.UNKNOWN
    details = error.details() if hasattr(error, "details") else str(error)
    cls = _BY_CODE.get(code, SoiqError)
    return cls(details or code.name, code, _field_of(error))


def _field_of(error):
    """The field soiqd named in the status details (soiq.v1.ErrorDetails), or ""."""
    trailers = error.trailing_metadata() if hasattr(error, "trailing_metadata") else None
    for key, value in trailers or ():
        if key == "grpc-status-details-bin":
            from soiq.v1 import soiq_pb2
            details = soiq_pb2.ErrorDetails()
            try:
                details.ParseFromString(value)
            except Exception:  # not ours: a proxy's google.rpc.Status with other details
                return ""
            return details.field
    return ""
