#include "render/window.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

namespace soiq::render {

namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

bool parse_finite(std::string_view s, double& out) {
  s = trimmed(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars takes no '+'
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size() && std::isfinite(out);
}

// The value below which a fraction `p` of `sorted_part` lies, interpolated between the two order
// statistics around p * (n - 1) (the usual "linear" definition, numpy's default). `values` is
// reordered: nth_element is O(n) where a sort of a whole volume would be O(n log n).
double percentile(std::vector<float>& values, double p) {
  const double position = p * static_cast<double>(values.size() - 1);
  const auto below = static_cast<size_t>(std::floor(position));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(below), values.end());
  const double low = values[below];
  if (below + 1 >= values.size()) return low;
  // After nth_element every element past `below` is >= it, so the next order statistic is their minimum.
  const double high = *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(below) + 1, values.end());
  return low + (position - static_cast<double>(below)) * (high - low);
}

bool is_nuclear(const std::string& modality) {
  std::string upper = modality;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return upper == "PT" || upper == "NM";
}

}  // namespace

Result<Window> parse_window(const std::string& text) {
  const size_t comma = text.find(',');
  Window window;
  if (comma == std::string::npos || !parse_finite(std::string_view(text).substr(0, comma), window.center) ||
      !parse_finite(std::string_view(text).substr(comma + 1), window.width)) {
    return invalid_argument("window '" + text + "' is not 'CENTRE,WIDTH' with two finite numbers (e.g. '40,400')");
  }
  if (window.width <= 0) {
    return invalid_argument("window '" + text + "' has a width of " + std::string(trimmed(text.substr(comma + 1))) +
                            "; the width must be > 0");
  }
  return window;
}

ColourMap colour_map_for_modality(const std::string& modality) {
  return is_nuclear(modality) ? ColourMap::kHot : ColourMap::kGray;
}

Window default_window(const std::vector<float>& values, const std::string& modality) {
  std::vector<float> finite;
  finite.reserve(values.size());
  for (float v : values) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  if (finite.empty()) return Window{0, 1};
  double low = 0, high = 0;
  if (is_nuclear(modality)) {
    // Uptake starts at zero; the top half percent saturates so that one hot voxel does not
    // flatten the rest of the lesion into black.
    high = percentile(finite, 0.995);
  } else {
    low = percentile(finite, 0.01);
    high = percentile(finite, 0.99);
  }
  if (!(high > low)) return Window{high, 1};  // a constant image (or no uptake): its value mid-grey
  return Window{(low + high) / 2, high - low};
}

uint8_t window_level(const Window& window, double value) {
  if (std::isnan(value)) return 0;
  // DICOM's LINEAR_EXACT (PS3.3 C.11.2.1.3.2): the window's edges are exactly centre -/+ width/2.
  // Plain LINEAR's "- 0.5" and "width - 1" assume integer stored values and a width of at least 1,
  // which a PET series in SUV (a window of 0..4) does not have.
  const double t = (value - (window.center - window.width / 2)) / window.width;
  if (!(t > 0)) return 0;
  if (t >= 1) return 255;
  return static_cast<uint8_t>(std::lround(t * 255));
}

Rgb colour_of(ColourMap map, uint8_t level) {
  if (map == ColourMap::kGray) return Rgb{level, level, level};
  // Red rises over the first third, green over the second, blue over the last: each channel only
  // grows, so luminance grows with the level and the colour bar reads as an order.
  const auto ramp = [level](int third) {
    const int v = 3 * static_cast<int>(level) - 255 * third;
    return static_cast<uint8_t>(std::clamp(v, 0, 255));
  };
  return Rgb{ramp(0), ramp(1), ramp(2)};
}

}  // namespace soiq::render
