#pragma once
// The options of `soiq convert` that ask for coverage fractions instead of a binary mask, shared by
// the mesh-file form (run here) and the stored-structure form (run on soiqd):
//   --fractional       the fraction of each voxel inside the surface (uint8 0-255: 0 wholly
//                      outside, 255 wholly inside)
//   --float32          the fractions as float32 0-1 instead of bytes
//   --oversample N     N x N lines across each voxel (1-8; exact along the rows), default 4

#include "core/base/status.h"

namespace soiq::cli {

inline constexpr int kDefaultOversample = 4;

struct FractionArgs {
  bool fractional = false;
  bool float32 = false;
  int oversample = 0;  // 0: not given

  int lines_per_voxel() const { return oversample > 0 ? oversample : kDefaultOversample; }
};

// When argv[i] is one of the options above, consumes it (and its value, advancing i) and returns
// true; false otherwise. INVALID_ARGUMENT for a missing or bad value.
Result<bool> parse_fraction_option(int argc, char** argv, int& i, FractionArgs& args);

// INVALID_ARGUMENT when --float32 or --oversample come without --fractional.
Status check_fraction_args(const FractionArgs& args);

}  // namespace soiq::cli
