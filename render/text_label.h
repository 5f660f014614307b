#pragma once
// One line of text on a cairo context, placed by an anchor (its left, centre or right; its top,
// middle or baseline at the given point), in DejaVu Sans through cairo's own text API (fontconfig
// picks a sans-serif face when DejaVu is missing). The overlays draw their letters and captions
// light on a dark halo so that they read on any grey; the plots draw them dark without one.
//
// Inputs   size: the font's size in pixels (cairo's user units at the context's current matrix).
// Cost     O(characters). Thread-safe on different contexts (cairo's toy font API is).
// Caveats  no shaping beyond what cairo's toy API does: right-to-left scripts come out unjoined.

#include <cairo.h>

#include <string>

#include "render/window.h"

namespace soiq::render {

enum class Anchor { kStart, kCentre, kEnd };  // horizontally left/centre/right; vertically top/middle/bottom

struct TextStyle {
  double size = 12;
  Rgb colour{255, 255, 255};
  bool bold = false;
  bool halo = false;  // a dark outline around each glyph
};

void draw_text(cairo_t* cr, const std::string& text, double x, double y, Anchor horizontal, Anchor vertical,
               const TextStyle& style);

// The advance width of `text` in pixels, for laying out before drawing.
double text_width(cairo_t* cr, const std::string& text, const TextStyle& style);

}  // namespace soiq::render
