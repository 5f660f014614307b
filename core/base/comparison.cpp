#include "core/base/comparison.h"

#include <cmath>
#include <utility>

namespace soiq {
const char* comparison_symbol(Comparison op) {
  switch (op) {
    case Comparison::kLess:
      return "<";
    case Comparison::kLessOrEqual:
      return "<=";
    case Comparison::kGreater:
      return ">";
    case Comparison::kGreaterOrEqual:
      return ">=";
    case Comparison::kEqual:
      return "==";
    case Comparison::kNotEqual:
      return "!=";
  }
  return "?";
}

std::optional<Comparison> comparison_of_symbol(std::string_view symbol) {
  for (const Comparison c : kComparisons) {
    if (symbol == comparison_symbol(c)) return c;
  }
  return std::nullopt;
}

const char* sql_operator(Comparison op) {
  if (op == Comparison::kEqual) return "=";
  return op == Comparison::kNotEqual ? "<>" : comparison_symbol(op);
}

bool compare(double value, Comparison op, double threshold) {
  if (std::isnan(value)) return false;
  switch (op) {
    case Comparison::kLess:
      return value < threshold;
    case Comparison::kLessOrEqual:
      return value <= threshold;
    case Comparison::kGreater:
      return value > threshold;
    case Comparison::kGreaterOrEqual:
      return value >= threshold;
    case Comparison::kEqual:
      return value == threshold;
    case Comparison::kNotEqual:
      return value != threshold;
  }
  return false;
}

}  // namespace soiq
