#pragma once
// The command line of `soiq query` as the API's QueryRequest (pure: no server involved).
//
// Stage 1 (structured): --patient GLOB --sex M|F|O --min-age Y --max-age Y
//   --birth-date-from D --birth-date-to D --study-date-from D --study-date-to D (YYYYMMDD, inclusive)
//   --modality M --description GLOB --name GLOB --laterality L|R
// Stage 2 (content): --where 'FEATURE OP NUMBER' (repeatable, AND), --select FEATURE (repeatable),
//   --order-by FEATURE [--desc], --limit N, --spacing S|SX,SY,SZ [--margin N] | --series-modality M,
//   --interpolation nearest|linear. FEATURE and predicates as client/feature_expression.h.
// Output: --format table|json|csv.
// Errors: INVALID_ARGUMENT for an unknown option, a missing or bad value, a malformed expression
// (saying what is wrong and at which column), --desc without --order-by.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

struct QueryArgs {
  soiq::v1::QueryRequest request;
  std::string format = "table";
};

// argv[0] is "query".
Result<QueryArgs> parse_query_args(int argc, char** argv);

// The feature columns of the rows, in the order the server returns their values: where, then
// select, then order_by (as feature_text gives them).
std::vector<std::string> query_feature_columns(const soiq::v1::QueryRequest& request);

// soiqd's message about a field of the request ("where[0]: unknown feature ...") in the words of
// the command line ("--where 'sphercity > 1': unknown feature ..."); other messages unchanged.
Status in_command_line_words(const Status& status, const soiq::v1::QueryRequest& request);

// The positions of `columns` to print: the first of each distinct name (an --order-by that repeats
// a --select, say, is shown once).
std::vector<size_t> distinct_columns(const std::vector<std::string>& columns);

}  // namespace soiq::cli
