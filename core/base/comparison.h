#pragma once
// The six comparisons of a query's conditions, once: the enum every layer uses (the API's
// ComparisonOp maps onto it in one switch, server/api/query_request.cpp), their symbols as the
// feature grammar reads and writes them (proto/text/feature_expression.h), their SQL operators
// (the store's stored-feature conditions) and their meaning on a number.

#include <optional>
#include <string_view>

namespace soiq {

enum class Comparison { kLess, kLessOrEqual, kGreater, kGreaterOrEqual, kEqual, kNotEqual };
inline constexpr Comparison kComparisons[] = {Comparison::kLess,    Comparison::kLessOrEqual,
                                              Comparison::kGreater, Comparison::kGreaterOrEqual,
                                              Comparison::kEqual,   Comparison::kNotEqual};

// "<", "<=", ">", ">=", "==", "!=".
const char* comparison_symbol(Comparison op);
// The comparison of a symbol above; nullopt for anything else.
std::optional<Comparison> comparison_of_symbol(std::string_view symbol);
// The same comparison in standard SQL: "=" for "==", "<>" for "!=", otherwise the symbol.
const char* sql_operator(Comparison op);
// `value op threshold`; NaN never matches (as in SQL, where NULL never does).
bool compare(double value, Comparison op, double threshold);

}  // namespace soiq
