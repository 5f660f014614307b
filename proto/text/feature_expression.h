#pragma once
// The text form of the features a query filters, selects and orders by (soiq query --where,
// --select, --order-by; soiqd's /soiq/v1/query where=, select=, order-by=), parsed into the API's
// FeatureRef and Predicate: one grammar for the command line and the HTTP API.
//
// Grammar (blanks allowed between tokens):
//   feature   := NAME | NAME '[' REGION ']' | NAME '[' REGION ',' IMAGE ']' | NAME '[' ',' IMAGE ']'
//              | 'asym' '(' feature ')'              the asymmetry index (L - R) / ((L + R) / 2)
//   predicate := feature OP NUMBER,  OP one of < <= > >= == !=
//   NAME  letters, digits and '_', starting with a letter ("voxel_volume_mm3", "mean")
//   REGION "inside", "shell:R" or "core:R" with R > 0 in mm
//   IMAGE  a modality ("PT") or a series uid ("1.2.840.1"): letters, digits, '.', '-', '_'
// Examples: "voxel_volume_mm3 > 50000", "mean[shell:5,PT] >= 2.5", "asym(voxel_volume_mm3)".
// Errors: INVALID_ARGUMENT "<what was expected> at column C of '<text>'" (columns from 1), or
// naming the bad region or number. Whether NAME is a known feature is the server's to say.
// Cost: O(length); pure and thread-safe.

#include <optional>
#include <string>

#include "core/base/comparison.h"
#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::proto_text {

Result<soiq::v1::FeatureRef> parse_feature(const std::string& text);
Result<soiq::v1::Predicate> parse_predicate(const std::string& text);

// The canonical text of a feature, which parse_feature reads back: "mean[shell:5,PT]",
// "asym(voxel_volume_mm3)", "mean[,PT]".
std::string feature_text(const soiq::v1::FeatureRef& feature);

// The API's comparison enum and soiq's (core/base/comparison.h), mapped in one place: nullopt for
// an unset or unknown value.
std::optional<Comparison> comparison_of(soiq::v1::ComparisonOp op);
soiq::v1::ComparisonOp proto_comparison(Comparison op);
// "<", "<=", ... for an operator; "?" for an unset one.
const char* comparison_text(soiq::v1::ComparisonOp op);

}  // namespace soiq::proto_text
