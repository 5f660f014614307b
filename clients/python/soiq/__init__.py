"""soiq: query medical images by the content of their structures of interest (soiqd's Python client).

    import soiq
    c = soiq.Client("127.0.0.1:50051")
    rows = c.query(name="GTV*", select=["voxel_volume_mm3", "mean[inside,PT]"])
"""

from soiq.client import Client
from soiq.errors import (AlreadyExists, Cancelled, DataLoss, DeadlineExceeded, FailedPrecondition, Internal,
                         InvalidArgument, NotFound, PermissionDenied, ResourceExhausted, SoiqError, Unauthenticated,
                         Unavailable)
from soiq.features import feature_text, parse_feature, parse_predicate

__all__ = ["Client", "SoiqError", "InvalidArgument", "NotFound", "AlreadyExists", "FailedPrecondition",
           "ResourceExhausted", "Unauthenticated", "PermissionDenied", "Unavailable", "DeadlineExceeded",
           "Cancelled", "DataLoss", "Internal", "feature_text", "parse_feature", "parse_predicate"]
