#include "core/geometry/dyadic_lattice.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace soiq {

std::optional<int> dyadic_lattice_exponent(const std::vector<Vec3>& points) {
  int fraction_bits = 0;
  double largest = 0;
  for (const Vec3& p : points) {
    for (const double x : p) {
      // |x| = significand 2^(exponent - 1075), read from the bits (frexp is a call per value).
      const auto bits = std::bit_cast<uint64_t>(x);
      const int biased = int((bits >> 52) & 0x7ff);
      if (biased == 0x7ff) return std::nullopt;  // infinity or NaN
      const uint64_t significand = (bits & ((uint64_t(1) << 52) - 1)) | (biased != 0 ? uint64_t(1) << 52 : 0);
      if (significand == 0) continue;  // +-0
      // The bits after the binary point that are not trailing zeros.
      const int exponent = std::max(biased, 1) - 1075;
      fraction_bits = std::max(fraction_bits, -(exponent + std::countr_zero(significand)));
      largest = std::max(largest, std::fabs(x));
    }
  }
  if (fraction_bits > 64 || !(std::ldexp(largest, fraction_bits) < kDyadicLatticeBound)) return std::nullopt;
  return fraction_bits;
}

}  // namespace soiq
