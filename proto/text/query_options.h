#pragma once
// The options of a two-stage query, in one table that every face reads: the command line's
// parser, help, man page and completion (`soiq query --min-age 40`, client/cli), the HTTP query's
// arguments and its errors (`GET /soiq/v1/query?min-age=40`, server/http) and, through the shared
// cases of tests/data/query_cases.json, the Python client (`c.query(min_age=40)`, clients/python).
// An option has one name, spelled by each face its own way: "--min-age", "min-age=", min_age.
//
// Each row says what the option sets in the API's QueryRequest (its field path, the one the API's
// errors name), how its value is read, and what it means; the rules between options (desc needs
// order-by, margin needs spacing, ...) are QueryRequestBuilder::finish's. Values are checked by the
// rules of their fields (core/base/field_rules.h) and the feature grammar (feature_expression.h),
// so a value the table takes, the API takes too (unless it names a feature the server lacks).
// Pure and thread-safe.

#include <set>
#include <span>
#include <string>
#include <string_view>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::proto_text {

struct QueryOption {
  std::string_view name;           // "min-age"
  std::string_view value;          // the value's placeholder ("Y"); "" for a flag (desc)
  std::string_view default_value;  // what holds when it is not given; "" for nothing
  std::string_view meaning;        // one line of help
  std::string_view field;          // the QueryRequest field it sets: "stage1.min_age_years"
  bool repeatable = false;         // where and select: each use adds one
  bool stage1 = false;             // a filter of the records (stage 1) rather than of the features
  // Reads `value` into `request`: INVALID_ARGUMENT with the reason alone ("'x' is not a number").
  Status (*apply)(const std::string& value, v1::QueryRequest& request) = nullptr;
};

// Every option, in help order.
std::span<const QueryOption> query_options();
// The option named `name` (without dashes), or nullptr.
const QueryOption* find_query_option(std::string_view name);
// The option whose field is `field` or holds it ("where" for "where[2].feature"), or nullptr.
const QueryOption* query_option_of_field(std::string_view field);

// Sets the grid's spacing from "S" or "SX,SY,SZ" in mm (each finite and > 0): spacing_mm when the
// three are equal, spacing_xyz otherwise. Shared with the conversions' --spacing.
Status set_grid_spacing(const std::string& text, v1::GridSpec& grid);

// A QueryRequest built option by option, whichever face they came from. Errors name the option
// as the face spells it: `dashes` "--" on the command line ("--limit 'x': ..."), "" in a URL.
class QueryRequestBuilder {
 public:
  explicit QueryRequestBuilder(std::string dashes) : dashes_(std::move(dashes)) {}

  // INVALID_ARGUMENT for an unknown option (with a suggestion), a non-repeatable option given
  // twice, or a value its row refuses.
  Status add(const std::string& name, const std::string& value);
  // The request, after the rules between options: desc needs order-by; margin needs spacing;
  // spacing and series-modality exclude each other; min-age <= max-age.
  Result<v1::QueryRequest> finish() const;
  // How this face spells `name`: "--min-age" or "min-age".
  std::string spelled(std::string_view name) const { return dashes_ + std::string(name); }

 private:
  std::string dashes_;
  v1::QueryRequest request_;
  std::set<std::string, std::less<>> given_;
};

}  // namespace soiq::proto_text
