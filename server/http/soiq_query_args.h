#pragma once
// The query arguments of GET /soiq/v1/query as the API's QueryRequest: the options of the one
// query table (proto/text/query_options.h), the names `soiq query` takes without their dashes
// (docs/INTEROP.md), so a query moves between the command line and a URL word for word: min-age=40,
// where=voxel_volume_mm3>1000 (repeatable), desc or desc=true|false.
// Errors: INVALID_ARGUMENT naming the argument, as the table gives them (unknown, given twice, a
// bad value, a malformed expression with its column, the rules between options); soiqd's
// parse_query then checks what only the server knows (the feature catalogue), as for gRPC.

#include <string>
#include <utility>
#include <vector>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server::http {

Result<v1::QueryRequest> parse_soiq_query_args(const std::vector<std::pair<std::string, std::string>>& args);

}  // namespace soiq::server::http
