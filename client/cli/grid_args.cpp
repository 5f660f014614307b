#include "client/cli/grid_args.h"

#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/record_args.h"
#include "proto/text/query_options.h"

namespace soiq::cli {

Result<bool> parse_grid_option(int argc, char** argv, int& i, GridArgs& a) {
  const std::string arg = argv[i];
  if (arg == "--spacing") {
    SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
    // The query table's reading of a spacing, so --spacing means the same to every command.
    const Status s = proto_text::set_grid_spacing(text, a.grid);
    if (!s.ok()) return Status(s.code(), "--spacing: " + s.message());
    ++a.given;
  } else if (arg == "--margin") {
    SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
    SOIQ_ASSIGN_OR_RETURN(const int m, parse_int(text, "--margin", 0, 1000000));
    a.grid.set_margin_voxels(m);
    a.margin_given = true;
  } else if (arg == "--series" && a.allow_series_uid) {
    SOIQ_ASSIGN_OR_RETURN(*a.grid.mutable_series_uid(), option_value(argc, argv, i));
    ++a.given;
  } else if (arg == "--series-modality") {
    SOIQ_ASSIGN_OR_RETURN(*a.grid.mutable_series_modality(), option_value(argc, argv, i));
    ++a.given;
  } else {
    return false;
  }
  return true;
}

Status check_grid_args(const GridArgs& a) {
  if (a.given > 1) {
    return invalid_argument(a.allow_series_uid ? "give one of --spacing, --series and --series-modality"
                                               : "give either --spacing or --series-modality, not both");
  }
  if (a.margin_given && a.grid.target_case() != soiq::v1::GridSpec::kSpacingMm &&
      a.grid.target_case() != soiq::v1::GridSpec::kSpacingXyz) {
    return invalid_argument("--margin goes with --spacing");
  }
  return ok_status();
}

}  // namespace soiq::cli
