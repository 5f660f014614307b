#include "core/features/asymmetry_index.h"

#include <cmath>
#include <string>

namespace soiq {

Result<double> asymmetry_index(double left, double right) {
  if (!std::isfinite(left) || !std::isfinite(right)) {
    return invalid_argument("asymmetry index needs finite values, got left " + std::to_string(left) + " and right " +
                            std::to_string(right));
  }
  const double sum = left + right;
  if (sum == 0) {
    return invalid_argument("asymmetry index is undefined when left + right = 0 (left " + std::to_string(left) +
                            ", right " + std::to_string(right) + ")");
  }
  return (left - right) / (sum / 2);
}

}  // namespace soiq
