#pragma once
// How intensities become grey levels or colours: a window (centre, width) as DICOM's VOI LUT
// defines it (PS3.3 C.11.2.1.3.2, LINEAR_EXACT: values at or below centre - width/2 are black, at
// or above centre + width/2 white, linear between; plain LINEAR's "- 0.5" and "width - 1" assume
// integer values and a width of at least 1, which a PET window in SUV does not have), and a
// colour map per modality.
//
// When a series carries no Window Center/Width (an uploaded image, a PET series), the default is
// robust: the 1st to 99th percentile of the finite values given (CT, MR, any image), or, for PET and
// NM, 0 to the 99.5th percentile, so the hottest voxels saturate instead of a few outliers
// flattening the rest. A constant image gets a width of 1 around its value.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::render {

struct Window {
  double center = 0;
  double width = 1;  // > 0
};

enum class ColourMap {
  kGray,  // black to white
  kHot,   // PET's: black, red, yellow, white (monotonic in luminance)
};

// "C,W" with W > 0, finite ("40,400"). INVALID_ARGUMENT naming the text otherwise.
Result<Window> parse_window(const std::string& text);

// PT and NM: kHot; anything else kGray.
ColourMap colour_map_for_modality(const std::string& modality);

// The robust default above for `values` (NaNs and infinities ignored; empty: centre 0, width 1).
Window default_window(const std::vector<float>& values, const std::string& modality);

// 0..255 for `value` through the window (LINEAR_EXACT above, rounded half away from zero); NaN is 0.
uint8_t window_level(const Window& window, double value);

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};
Rgb colour_of(ColourMap map, uint8_t level);

}  // namespace soiq::render
