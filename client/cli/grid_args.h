#pragma once
// The target grid of a remote conversion on the command line (the API's GridSpec):
//   --spacing S|SX,SY,SZ [--margin N]   an axis-aligned grid around the surface (mm, voxels)
//   --series UID                         a stored image series (convert and features only)
//   --series-modality M                  the series of the structure's study with modality M
// None given: the server's default (1 mm, margin 2).

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

struct GridArgs {
  soiq::v1::GridSpec grid;
  bool allow_series_uid = true;  // false for queries: a series belongs to one study
  int given = 0;                 // how many of --spacing, --series, --series-modality
  bool margin_given = false;
};

// When argv[i] is one of the options above, stores it (advancing i) and returns true.
Result<bool> parse_grid_option(int argc, char** argv, int& i, GridArgs& args);

// INVALID_ARGUMENT when more than one target is given, or --margin without --spacing.
Status check_grid_args(const GridArgs& args);

}  // namespace soiq::cli
