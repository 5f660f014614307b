#include "client/cli/fraction_args.h"

#include <string>

#include "client/cli/cli_args.h"
#include "core/voxelize/coverage_1d.h"

namespace soiq::cli {

Result<bool> parse_fraction_option(int argc, char** argv, int& i, FractionArgs& a) {
  const std::string arg = argv[i];
  if (arg == "--fractional") {
    a.fractional = true;
  } else if (arg == "--float32") {
    a.float32 = true;
  } else if (arg == "--oversample") {
    if (i + 1 >= argc) return invalid_argument("--oversample needs a value");
    SOIQ_ASSIGN_OR_RETURN(a.oversample, parse_int(argv[++i], "--oversample", 1, kMaxLinesPerVoxel));
  } else {
    return false;
  }
  return true;
}

Status check_fraction_args(const FractionArgs& a) {
  if (!a.fractional && (a.float32 || a.oversample > 0)) {
    return invalid_argument(std::string(a.float32 ? "--float32" : "--oversample") +
                            " applies to coverage fractions: add --fractional");
  }
  return ok_status();
}

}  // namespace soiq::cli
