#include "render/plot_scales.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace soiq::render {

namespace {

constexpr int kFewestBins = 5, kMostBins = 50;

// The value below which a fraction p of the sorted values lies, interpolated (numpy's "linear").
double sorted_quantile(const std::vector<double>& sorted, double p) {
  const double position = p * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<size_t>(std::floor(position));
  if (below + 1 >= sorted.size()) return sorted[below];
  return sorted[below] + (position - static_cast<double>(below)) * (sorted[below + 1] - sorted[below]);
}

}  // namespace

int histogram_bins(std::vector<double> values) {
  if (values.size() < 2) return kFewestBins;
  std::sort(values.begin(), values.end());
  const double range = values.back() - values.front();
  if (!(range > 0)) return kFewestBins;
  const double n = static_cast<double>(values.size());
  const double iqr = sorted_quantile(values, 0.75) - sorted_quantile(values, 0.25);
  const double bins = iqr > 0 ? std::ceil(range / (2 * iqr / std::cbrt(n))) : std::ceil(std::log2(n)) + 1;
  return static_cast<int>(std::clamp(bins, double{kFewestBins}, double{kMostBins}));
}

std::vector<double> round_ticks(double low, double high, int most, double min_step) {
  if (!std::isfinite(low) || !std::isfinite(high) || low > high || most < 1) return {};
  if (low == high) return {low};
  double step = std::max(min_step, (high - low) / std::max(1, most));
  const double decade = std::pow(10.0, std::floor(std::log10(step)));
  for (double factor : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    if (factor * decade >= step * (1 - 1e-9)) {
      step = factor * decade;
      break;
    }
  }
  // Ticks as integer multiples of the step, so that rounding does not accumulate along the axis.
  const double first = std::ceil(low / step - 1e-9), last = std::floor(high / step + 1e-9);
  std::vector<double> ticks;
  for (double i = first; i <= last; ++i) ticks.push_back(i * step == 0 ? 0.0 : i * step);  // no "-0"
  return ticks;
}

std::string tick_label(double value) {
  if (value == 0) return "0";  // and never "-0"
  const auto close = [value](const char* text) {
    return std::abs(std::strtod(text, nullptr) - value) <= 1e-9 * std::abs(value);
  };
  char text[64];
  // Plain decimals where an axis reader expects them ("1500", "0.02"), exponents beyond.
  if (std::abs(value) >= 1e-4 && std::abs(value) < 1e6) {
    for (int decimals = 0; decimals <= 12; ++decimals) {
      std::snprintf(text, sizeof text, "%.*f", decimals, value);
      if (close(text)) return text;
    }
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (close(text)) break;
  }
  return text;
}

std::string plot_title(const std::string& title, int64_t plotted, int64_t without_value) {
  std::string counts = std::to_string(plotted) + (plotted == 1 ? " row" : " rows");
  if (without_value > 0) counts += ", " + std::to_string(without_value) + " without a value";
  return title.empty() ? counts : title + " \u2014 " + counts;
}

std::string axis_label(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " (" + unit + ")";
}

PlotFrame plot_frame(int width, int height) {
  PlotFrame frame;
  frame.left = std::max(64.0, 0.11 * width);
  frame.right = width - std::max(24.0, 0.04 * width);
  frame.top = std::max(44.0, 0.09 * height);
  frame.bottom = height - std::max(56.0, 0.11 * height);
  return frame;
}

AxisRange scatter_range(double low, double high) {
  if (!(high > low)) return {low - 1, low + 1};
  const double pad = 0.05 * (high - low);
  return {low - pad, high + pad};
}

}  // namespace soiq::render
