#include "client/cli/remote_features_command.h"

#include <unistd.h>

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/feature_report_output.h"
#include "client/cli/grid_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "core/regions/regions.h"

namespace soiq::cli {

namespace {

struct RemoteFeaturesArgs {
  soiq::v1::FeaturesRequest request;
  std::string format = "table";
};

Result<RemoteFeaturesArgs> parse_remote_features_args(int argc, char** argv) {
  RemoteFeaturesArgs a;
  GridArgs grid;
  std::string id;
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool is_grid, parse_grid_option(argc, argv, i, grid));
    if (is_grid) continue;
    const std::string arg = argv[i];
    if (arg == "--features") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      size_t from = 0;
      for (size_t comma; (comma = text.find(',', from)) != std::string::npos; from = comma + 1) {
        if (comma > from) a.request.add_features(text.substr(from, comma - from));
      }
      if (from < text.size()) a.request.add_features(text.substr(from));
    } else if (arg == "--region") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      SOIQ_RETURN_IF_ERROR(parse_region(text).status());  // the same words offline and remote
      a.request.add_regions(text);
    } else if (arg == "--image") {
      SOIQ_ASSIGN_OR_RETURN(*a.request.add_images(), option_value(argc, argv, i));
    } else if (arg == "--interpolation") {
      SOIQ_ASSIGN_OR_RETURN(const std::string text, option_value(argc, argv, i));
      if (text != "nearest" && text != "linear") return invalid_argument("--interpolation must be nearest or linear");
      a.request.set_interpolation(text == "linear" ? soiq::v1::LINEAR : soiq::v1::NEAREST);
    } else if (arg == "--format") {
      SOIQ_ASSIGN_OR_RETURN(a.format, option_value(argc, argv, i));
      if (a.format != "table" && a.format != "json" && a.format != "csv") {
        return invalid_argument("--format must be table, json or csv");
      }
    } else if (arg == "--label" || arg == "--reference" || arg == "--robust" || arg == "--ras" || arg == "--ibsi" ||
               arg == "--threads" || arg == "--even-odd") {
      return invalid_argument(arg + " applies to a local file, not to a stored structure");
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalid_argument("unknown option '" + arg + "'");
    } else if (id.empty()) {
      id = arg;
    } else {
      return invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  SOIQ_ASSIGN_OR_RETURN(const int64_t structure_id, parse_structure_id(id));
  a.request.set_structure_id(structure_id);
  SOIQ_RETURN_IF_ERROR(check_grid_args(grid));
  if (grid.given || grid.margin_given) *a.request.mutable_grid() = grid.grid;
  return a;
}

// The API's answer as the report the offline command prints.
FeatureReport to_report(const soiq::v1::FeaturesResponse& r) {
  FeatureReport report;
  for (const soiq::v1::FeatureValue& f : r.features()) {
    report.features.push_back({f.name(), {f.value().begin(), f.value().end()}, f.region(), f.image()});
  }
  for (const soiq::v1::Timing& t : r.timings()) report.timings_ms.emplace_back(t.part(), t.milliseconds());
  return report;
}

Status features(const RemoteFeaturesArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  const Result<soiq::v1::FeaturesResponse> computed = c.compute_features(a.request);
  if (!computed.ok() && interrupted()) return interrupted_by_user("no values were printed");
  SOIQ_ASSIGN_OR_RETURN(const soiq::v1::FeaturesResponse r, computed);
  print_feature_report(to_report(r), a.format);
  if (r.from_cache() && isatty(fileno(stderr))) std::fputs("(from soiqd's feature cache)\n", stderr);
  return ok_status();
}

}  // namespace

int run_remote_features_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command(
      "features", parse_remote_features_args(argc, argv), remote,
      [](const RemoteFeaturesArgs& a, const client::ClientOptions& options) { return features(a, options); });
}

}  // namespace soiq::cli
