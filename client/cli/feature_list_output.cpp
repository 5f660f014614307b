#include "client/cli/feature_list_output.h"

#include <algorithm>
#include <cstdio>

#include "core/features/feature_catalogue.h"
#include "proto/text/query_columns.h"

namespace soiq::cli {

std::vector<FeatureListRow> catalogue_rows() {
  std::vector<FeatureListRow> rows;
  for (const FeatureDef& f : feature_catalogue()) {
    rows.push_back({std::string(f.name), std::string(family_name(f.family)), std::string(f.unit),
                    std::string(feature_needs(f)), std::string(f.summary), f.version});
  }
  return rows;
}

std::vector<FeatureListRow> server_rows(const soiq::v1::ServerInfo& info) {
  std::vector<FeatureListRow> rows;
  for (const soiq::v1::FeatureInfo& f : info.features())
    rows.push_back({f.name(), f.family(), f.unit(), f.needs(), f.summary(), f.version()});
  return rows;
}

void print_feature_list(const std::vector<FeatureListRow>& rows, const std::string& format) {
  if (format == "csv") {
    // soiq's one CSV writer (the summaries hold commas and quotes).
    std::fputs(proto_text::csv_line({"name", "family", "unit", "needs", "summary", "version"}).c_str(), stdout);
    for (const FeatureListRow& r : rows) {
      std::fputs(
          proto_text::csv_line({r.name, r.family, r.unit, r.needs, r.summary, std::to_string(r.version)}).c_str(),
          stdout);
    }
    return;
  }
  if (format == "markdown") {
    std::puts("| name | family | unit | needs | definition | version |");
    std::puts("|---|---|---|---|---|---:|");
    for (const FeatureListRow& r : rows) {
      std::printf("| `%s` | %s | %s | %s | %s | %d |\n", r.name.c_str(), r.family.c_str(), r.unit.c_str(),
                  r.needs.c_str(), r.summary.c_str(), r.version);
    }
    return;
  }
  size_t width = 4;
  for (const FeatureListRow& r : rows) width = std::max(width, r.name.size());
  std::printf("%-*s  %-11s  %-7s  %s\n", int(width), "name", "family", "unit", "definition");
  for (const FeatureListRow& r : rows) {
    std::printf("%-*s  %-11s  %-7s  %s\n", int(width), r.name.c_str(), r.family.c_str(),
                r.unit.empty() ? "-" : r.unit.c_str(), r.summary.c_str());
  }
  std::puts("\nBeside a stored surface, each surface feature's value on the mask's surface is mask_<name>.");
}

}  // namespace soiq::cli
