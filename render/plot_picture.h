#pragma once
// A cohort's answer as a plot, one mark per row: a histogram of one feature (bins by the
// Freedman-Diaconis rule, at least 5 and at most 50; the count on the y axis) or a scatter of two.
// Axes are named with the feature and its unit ("voxel_volume_mm3 (mm3)"), ticks at round values
// (1, 2 or 5 x 10^n), and the number of rows plotted in the title. Rows without a finite value for
// a plotted feature are left out and counted in the title ("48 rows, 2 without a value": 48
// plotted, 2 more left out). The numbers (bins, ticks, title, the data area) are plot_scales.h's.
//
// Errors   INVALID_ARGUMENT for other than 1 or 2 axes, axes of different lengths, a size outside
//          200..kMaxPictureSide; those of draw_picture. No finite value at all is drawn as empty axes
//          saying so, not an error: a query may match nothing.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "render/picture.h"

namespace soiq::render {

struct PlotAxis {
  std::string name;            // the feature as selected: "mean[inside,PT]"
  std::string unit;            // "mm3", "HU", "" (none)
  std::vector<double> values;  // one per row; NaN: no value
};

Result<std::string> plot_picture(const std::vector<PlotAxis>& axes, const std::string& title, int width, int height,
                                 const PictureOptions& options);

}  // namespace soiq::render
