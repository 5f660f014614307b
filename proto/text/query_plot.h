#pragma once
// What a query's plot shows (`soiq query --plot`, GET /soiq/v1/query/plot): the first selected
// feature as a histogram, or the first two as a scatter, one mark per row; without --select, the
// query's first one or two feature columns (where's, then order_by's). Each axis is named as the
// column is (feature_text) with its unit: the catalogue's for shape features ("mm3", "1/mm"), for
// intensity features the image's ("HU" for CT, "SUV" for PT: soiq stores PET in SUV body weight
// where the files allow it, dicom/pet_suv.h; none for other modalities, whose intensities have no
// common unit), none for an asymmetry index (a ratio).
//
// Errors   INVALID_ARGUMENT when the query names no feature ("select one") or a plotted
//          feature has several values per row (a point: plot one of its components' features).
// Cost     O(rows). Pure.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::proto_text {

struct PlotColumn {
  std::string name;  // feature_text: "mean[inside,PT]"
  std::string unit;
  std::vector<double> values;  // per row; NaN where the row has none
};

// `value(row, k)`: row's k-th value in request order (QueryRow.values) when it has exactly one.
Result<std::vector<PlotColumn>> query_plot_columns(
    const v1::QueryRequest& request, size_t rows,
    const std::function<std::optional<double>(size_t row, size_t k)>& value);

// The unit of a feature as an axis names it (above).
std::string feature_unit(const v1::FeatureRef& feature);

}  // namespace soiq::proto_text
