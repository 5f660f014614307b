#pragma once
// The command line of `soiq query` as the API's QueryRequest (pure: no server involved): every
// option of the one query table (proto/text/query_options.h) as --NAME VALUE (--desc alone), plus
// --format table|json|csv for the rows' output and --plot FILE.png|.svg (proto/text/query_plot.h
// says what is drawn; the file's extension its format).
// Errors: INVALID_ARGUMENT for an unknown option, a missing or bad value, a malformed expression
// (saying what is wrong and at which column), and the table's rules between options (--desc
// without --order-by, ...), each naming the option as it was typed.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

struct QueryArgs {
  soiq::v1::QueryRequest request;
  std::string format = "table";
  std::string plot;  // "" for none
};

// argv[0] is "query".
Result<QueryArgs> parse_query_args(int argc, char** argv);

// soiqd's error about a field of the request (Status::field(): "where[0]", "stage1.min_age_years")
// in the words of the command line ("--where 'sphercity > 1': unknown feature ...", "--min-age:
// ..."), from the field's path and the table, never from the message's prose; others unchanged.
Status in_command_line_words(const Status& status, const soiq::v1::QueryRequest& request);

}  // namespace soiq::cli
