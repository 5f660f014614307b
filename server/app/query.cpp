#include "server/app/query.h"

#include <cmath>

namespace soiq::server {

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

}  // namespace soiq::server
