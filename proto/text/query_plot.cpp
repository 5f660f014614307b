#include "proto/text/query_plot.h"

#include <cmath>

#include "core/features/feature_catalogue.h"
#include "proto/text/feature_expression.h"

namespace soiq::proto_text {
namespace {

const FeatureDef* definition(const v1::FeatureRef& f) {
  if (const FeatureDef* d = find_shape_feature(f.name())) return d;
  if (const FeatureDef* d = find_intensity_feature(f.name())) return d;
  return mask_feature(f.name());
}

}  // namespace

std::string feature_unit(const v1::FeatureRef& f) {
  if (f.asymmetry()) return "";
  const FeatureDef* d = definition(f);
  if (d == nullptr) return "";
  if (d->unit != "image") return std::string(d->unit);
  if (f.image() == "CT") return "HU";
  if (f.image() == "PT") return "SUV";
  return "";
}

Result<std::vector<PlotColumn>> query_plot_columns(
    const v1::QueryRequest& request, size_t rows,
    const std::function<std::optional<double>(size_t row, size_t k)>& value) {
  // Each feature with its place in a row's values: where's, select's, order_by.
  std::vector<std::pair<v1::FeatureRef, size_t>> chosen;
  const size_t first_select = size_t(request.where_size());
  for (int i = 0; i < request.select_size() && chosen.size() < 2; ++i)
    chosen.emplace_back(request.select(i), first_select + size_t(i));
  if (chosen.empty()) {
    std::vector<std::pair<v1::FeatureRef, size_t>> others;
    for (int i = 0; i < request.where_size(); ++i) others.emplace_back(request.where(i).feature(), size_t(i));
    if (request.has_order_by()) others.emplace_back(request.order_by(), first_select + size_t(request.select_size()));
    for (const auto& other : others) {
      const bool again = !chosen.empty() && feature_text(chosen[0].first) == feature_text(other.first);
      if (!again && chosen.size() < 2) chosen.push_back(other);
    }
  }
  if (chosen.empty()) return invalid_argument("the plot needs a feature: select one (two for a scatter)");
  std::vector<PlotColumn> columns;
  for (const auto& [feature, k] : chosen) {
    const FeatureDef* d = definition(feature);
    if (!feature.asymmetry() && d != nullptr && d->components != 1)
      return invalid_argument("'" + feature_text(feature) + "' has " + std::to_string(d->components) +
                              " values per structure; plot features of one value");
    PlotColumn c{feature_text(feature), feature_unit(feature), {}};
    c.values.reserve(rows);
    for (size_t r = 0; r < rows; ++r) {
      c.values.push_back(value(r, k).value_or(std::nan("")));
    }
    columns.push_back(std::move(c));
  }
  return columns;
}

}  // namespace soiq::proto_text
