#pragma once
// Prints a feature catalogue: core's own (`soiq features --list`, offline) or the one a soiqd
// reports (`soiq info --features`), as a table, CSV or the Markdown table of docs/FEATURES.md,
// which a test compares with this output so that the docs cannot drift from the code.

#include <string>
#include <vector>

#include "soiq/v1/soiq.pb.h"

namespace soiq::cli {

struct FeatureListRow {
  std::string name, family, unit, needs, summary;
  int version = 1;
};

// core/features/feature_catalogue.h, in report order.
std::vector<FeatureListRow> catalogue_rows();
// What a soiqd reports in ServerInfo.features.
std::vector<FeatureListRow> server_rows(const soiq::v1::ServerInfo& info);

// `format`: "table", "csv" or "markdown"; the caller has checked it.
void print_feature_list(const std::vector<FeatureListRow>& rows, const std::string& format);

}  // namespace soiq::cli
