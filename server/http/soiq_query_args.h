#pragma once
// The query arguments of GET /soiq/v1/query as the API's QueryRequest: the options of `soiq query`
// under the same names without their dashes in front (docs/INTEROP.md), so a query moves between
// the command line and a URL word for word.
//
//   patient sex min-age max-age birth-date-from birth-date-to study-date-from study-date-to
//   modality description name laterality        stage 1, as soiq query's options
//   where (repeatable) select (repeatable) order-by desc=true|false limit
//   spacing (S or SX,SY,SZ) margin series-modality interpolation=nearest|linear
//
// Features and predicates in the grammar of proto/text/feature_expression.h. Values are checked
// here for form only (numbers, one value per key but where and select); soiqd's parse_query checks
// their meaning as for gRPC.
// Errors: INVALID_ARGUMENT naming the argument: unknown, given twice, not a number, a malformed
// expression (with its column), desc without order-by, margin without spacing, both spacing and
// series-modality.

#include <string>
#include <utility>
#include <vector>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server::http {

Result<v1::QueryRequest> parse_soiq_query_args(const std::vector<std::pair<std::string, std::string>>& args);

}  // namespace soiq::server::http
