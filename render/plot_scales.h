#pragma once
// The numbers behind a plot (render/plot_picture.h), apart from the drawing so that they can be
// checked: how many histogram bins, where the ticks go, the title line, and where the data area sits
// in the picture.
//
// Cost     histogram_bins O(n log n); the rest O(1) or O(ticks). Thread-safe (pure functions).

#include <cstdint>
#include <string>
#include <vector>

namespace soiq::render {

// Freedman and Diaconis (1981): bins of width 2 IQR / n^(1/3) over the values' range, at least 5
// and at most 50. When the IQR is 0 (over half the values equal) the rule has no width; Sturges'
// ceil(log2 n) + 1 stands in. `values` are finite; 5 for fewer than 2 values or a zero range.
int histogram_bins(std::vector<double> values);

// Ticks at the multiples of a round step that lie in [low, high]: the smallest 1, 2 or 5 x 10^n
// that is at least (high - low) / most and at least `min_step` (1 for counts), so about `most`
// intervals and never more than most + 1 ticks. Empty when low > high or either is not finite; the
// one value when low == high.
std::vector<double> round_ticks(double low, double high, int most, double min_step = 0);

// A tick's label: the fewest decimals that show the value (0.30000000000000004 is "0.3", 1500 is
// "1500"); below 1e-4 and from 1e6 on, the fewest significant digits with an exponent ("2.5e-05").
std::string tick_label(double value);

// "volume — 48 rows, 2 without a value": the caller's title, then the rows plotted and, when some
// rows lack a finite value for a plotted feature, how many were left out. No title: the counts alone.
std::string plot_title(const std::string& title, int64_t plotted, int64_t without_value);

// "voxel_volume_mm3 (mm3)"; the name alone without a unit.
std::string axis_label(const std::string& name, const std::string& unit);

// The data area of a width x height plot, in pixels from the top left: margins hold the title, the
// tick labels and the axis labels.
struct PlotFrame {
  double left = 0, top = 0, right = 0, bottom = 0;
};
PlotFrame plot_frame(int width, int height);

// A scatter's axis range for data in [low, high]: 5 % of the range added on each side, so that no
// mark sits on the frame; 1 on each side for a single value.
struct AxisRange {
  double low = 0, high = 1;
};
AxisRange scatter_range(double low, double high);

}  // namespace soiq::render
