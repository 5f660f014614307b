#include "render/plot_picture.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/plot_scales.h"
#include "render/text_label.h"

namespace soiq::render {

namespace {

constexpr Rgb kInk{32, 32, 32}, kGrid{225, 225, 225}, kMark{31, 119, 180};

struct PlotData {
  std::vector<std::vector<double>> columns;  // per axis, the rows with a finite value on every axis
  int64_t without_value = 0;
};

PlotData finite_rows(const std::vector<PlotAxis>& axes) {
  PlotData data;
  data.columns.resize(axes.size());
  for (size_t row = 0; row < axes.front().values.size(); ++row) {
    const bool finite =
        std::all_of(axes.begin(), axes.end(), [row](const PlotAxis& a) { return std::isfinite(a.values[row]); });
    if (!finite) {
      ++data.without_value;
      continue;
    }
    for (size_t a = 0; a < axes.size(); ++a) data.columns[a].push_back(axes[a].values[row]);
  }
  return data;
}

// Maps data values to pixels along one side of the frame.
struct Scale {
  double low, high, from_px, to_px;
  double operator()(double v) const { return from_px + (v - low) / (high - low) * (to_px - from_px); }
};

void set_colour(cairo_t* cr, const Rgb& c, double alpha = 1) {
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
}

// Grid lines, ticks and their labels on both axes, the frame, and the axis labels.
void draw_axes(cairo_t* cr, const PlotFrame& f, const Scale& x, const std::vector<double>& x_ticks, const Scale& y,
               const std::vector<double>& y_ticks, const std::string& x_label, const std::string& y_label,
               double font) {
  TextStyle text{font, kInk, false, false};
  cairo_set_line_width(cr, 1);
  set_colour(cr, kGrid);
  // Half-pixel offsets put 1 px lines on whole pixels.
  for (double t : x_ticks) {
    cairo_move_to(cr, std::round(x(t)) + 0.5, f.top);
    cairo_line_to(cr, std::round(x(t)) + 0.5, f.bottom);
  }
  for (double t : y_ticks) {
    cairo_move_to(cr, f.left, std::round(y(t)) + 0.5);
    cairo_line_to(cr, f.right, std::round(y(t)) + 0.5);
  }
  cairo_stroke(cr);
  set_colour(cr, kInk);
  const double tick = font * 0.4;
  for (double t : x_ticks) {
    cairo_move_to(cr, std::round(x(t)) + 0.5, f.bottom);
    cairo_line_to(cr, std::round(x(t)) + 0.5, f.bottom + tick);
    draw_text(cr, tick_label(t), x(t), f.bottom + tick + 2, Anchor::kCentre, Anchor::kStart, text);
  }
  for (double t : y_ticks) {
    cairo_move_to(cr, f.left - tick, std::round(y(t)) + 0.5);
    cairo_line_to(cr, f.left, std::round(y(t)) + 0.5);
    draw_text(cr, tick_label(t), f.left - tick - 3, y(t), Anchor::kEnd, Anchor::kCentre, text);
  }
  cairo_stroke(cr);
  draw_text(cr, x_label, (f.left + f.right) / 2, f.bottom + tick + 2 + font * 1.5, Anchor::kCentre, Anchor::kStart,
            text);
  cairo_save(cr);
  cairo_translate(cr, font * 0.5, (f.top + f.bottom) / 2);
  cairo_rotate(cr, -std::numbers::pi / 2);
  draw_text(cr, y_label, 0, 0, Anchor::kCentre, Anchor::kStart, text);
  cairo_restore(cr);
}

// Last, so that no bar or mark covers the axes.
void draw_frame(cairo_t* cr, const PlotFrame& f) {
  set_colour(cr, kInk);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, std::round(f.left) + 0.5, std::round(f.top) + 0.5, std::round(f.right - f.left),
                  std::round(f.bottom - f.top));
  cairo_stroke(cr);
}

// About one tick per `spacing` pixels.
int tick_count(double length_px, double spacing) { return std::max(2, static_cast<int>(length_px / spacing)); }

void draw_histogram(cairo_t* cr, const PlotFrame& f, const std::vector<double>& values, const PlotAxis& axis,
                    double font) {
  const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
  // A single value gets a unit-wide range around it, so its bar has a width.
  const double low = *highest > *lowest ? *lowest : *lowest - 0.5, high = *highest > *lowest ? *highest : *lowest + 0.5;
  const int bins = histogram_bins(values);
  std::vector<int64_t> counts(static_cast<size_t>(bins), 0);
  for (double v : values) {
    const auto bin = static_cast<int64_t>(std::floor((v - low) / (high - low) * bins));
    ++counts[static_cast<size_t>(std::clamp<int64_t>(bin, 0, bins - 1))];  // the maximum closes the last bin
  }
  const double most = static_cast<double>(*std::max_element(counts.begin(), counts.end()));
  const std::vector<double> y_ticks = round_ticks(0, most, tick_count(f.bottom - f.top, 50), 1);
  const double y_top = std::max(most, y_ticks.empty() ? 1.0 : y_ticks.back()) * 1.05;
  const Scale x{low, high, f.left, f.right}, y{0, y_top, f.bottom, f.top};
  const std::vector<double> x_ticks = round_ticks(low, high, tick_count(f.right - f.left, 70));
  draw_axes(cr, f, x, x_ticks, y, y_ticks, axis_label(axis.name, axis.unit), "rows", font);
  for (int b = 0; b < bins; ++b) {
    if (counts[static_cast<size_t>(b)] == 0) continue;
    const double left = x(low + (high - low) * b / bins), right = x(low + (high - low) * (b + 1) / bins);
    cairo_rectangle(cr, left, y(static_cast<double>(counts[static_cast<size_t>(b)])), right - left,
                    f.bottom - y(static_cast<double>(counts[static_cast<size_t>(b)])));
  }
  set_colour(cr, kMark);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);  // white edges keep neighbouring bars apart
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
}

void draw_scatter(cairo_t* cr, const PlotFrame& f, const PlotData& data, const std::vector<PlotAxis>& axes, double font,
                  double mark_radius) {
  const auto [x_min, x_max] = std::minmax_element(data.columns[0].begin(), data.columns[0].end());
  const auto [y_min, y_max] = std::minmax_element(data.columns[1].begin(), data.columns[1].end());
  const AxisRange xr = scatter_range(*x_min, *x_max), yr = scatter_range(*y_min, *y_max);
  const Scale x{xr.low, xr.high, f.left, f.right}, y{yr.low, yr.high, f.bottom, f.top};
  draw_axes(cr, f, x, round_ticks(xr.low, xr.high, tick_count(f.right - f.left, 70)), y,
            round_ticks(yr.low, yr.high, tick_count(f.bottom - f.top, 50)), axis_label(axes[0].name, axes[0].unit),
            axis_label(axes[1].name, axes[1].unit), font);
  // Translucent marks: where rows pile up the colour deepens.
  set_colour(cr, kMark, 0.75);
  for (size_t row = 0; row < data.columns[0].size(); ++row) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, x(data.columns[0][row]), y(data.columns[1][row]), mark_radius, 0, 2 * std::numbers::pi);
    cairo_fill(cr);
  }
}

}  // namespace

Result<std::string> plot_picture(const std::vector<PlotAxis>& axes, const std::string& title, int width, int height,
                                 const PictureOptions& options) {
  if (axes.size() != 1 && axes.size() != 2) {
    return invalid_argument("a plot takes 1 feature (a histogram) or 2 (a scatter), not " +
                            std::to_string(axes.size()));
  }
  if (axes.size() == 2 && axes[0].values.size() != axes[1].values.size()) {
    return invalid_argument("the plot's features have " + std::to_string(axes[0].values.size()) + " and " +
                            std::to_string(axes[1].values.size()) + " values; each needs one per row");
  }
  if (width < 200 || height < 200 || width > kMaxPictureSide || height > kMaxPictureSide) {
    return invalid_argument("a plot of " + std::to_string(width) + " x " + std::to_string(height) +
                            " px is out of range; each side must be 200.." + std::to_string(kMaxPictureSide) + " px");
  }
  const PlotData data = finite_rows(axes);
  const auto plotted = static_cast<int64_t>(data.columns[0].size());
  return draw_picture(width, height, options, [&](cairo_t* cr) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    const PlotFrame f = plot_frame(width, height);
    const double font = std::clamp(height / 42.0, 10.0, 18.0);
    draw_text(cr, plot_title(title, plotted, data.without_value), width / 2.0, f.top / 2, Anchor::kCentre,
              Anchor::kCentre, TextStyle{font * 1.15, kInk, true, false});
    if (plotted == 0) {
      // A query may match nothing: empty axes that say so, not an error.
      const Scale unit{0, 1, f.left, f.right}, unit_y{0, 1, f.bottom, f.top};
      draw_axes(cr, f, unit, {}, unit_y, {}, axis_label(axes[0].name, axes[0].unit),
                axes.size() == 2 ? axis_label(axes[1].name, axes[1].unit) : "rows", font);
      draw_text(cr, "no row has a value to plot", (f.left + f.right) / 2, (f.top + f.bottom) / 2, Anchor::kCentre,
                Anchor::kCentre, TextStyle{font, kInk, false, false});
      draw_frame(cr, f);
      return;
    }
    if (axes.size() == 1) {
      draw_histogram(cr, f, data.columns[0], axes[0], font);
    } else {
      draw_scatter(cr, f, data, axes, font, std::clamp(std::min(width, height) / 120.0, 3.0, 7.0));
    }
    draw_frame(cr, f);
  });
}

}  // namespace soiq::render
