#include "render/text_label.h"

#include <algorithm>

namespace soiq::render {

namespace {

void select_font(cairo_t* cr, const TextStyle& style) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         style.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, style.size);
}

double anchored(double at, double extent, Anchor anchor) {
  switch (anchor) {
    case Anchor::kStart:
      return at;
    case Anchor::kCentre:
      return at - extent / 2;
    case Anchor::kEnd:
      break;
  }
  return at - extent;
}

}  // namespace

double text_width(cairo_t* cr, const std::string& text, const TextStyle& style) {
  cairo_save(cr);
  select_font(cr, style);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  cairo_restore(cr);
  return extents.x_advance;
}

void draw_text(cairo_t* cr, const std::string& text, double x, double y, Anchor horizontal, Anchor vertical,
               const TextStyle& style) {
  if (text.empty()) return;
  cairo_save(cr);
  select_font(cr, style);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  cairo_font_extents_t font;
  cairo_font_extents(cr, &font);
  // Vertical placement by the font's ascent and descent, not the string's own ink, so that "k 42"
  // and "A" sit on the same line.
  const double left = anchored(x, extents.x_advance, horizontal);
  const double top = anchored(y, font.ascent + font.descent, vertical);
  cairo_move_to(cr, left, top + font.ascent);
  cairo_text_path(cr, text.c_str());
  if (style.halo) {
    cairo_set_source_rgba(cr, 0, 0, 0, 0.85);
    cairo_set_line_width(cr, std::max(2.0, style.size / 5));
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke_preserve(cr);
  }
  cairo_set_source_rgb(cr, style.colour.r / 255.0, style.colour.g / 255.0, style.colour.b / 255.0);
  cairo_fill(cr);
  cairo_restore(cr);
}

}  // namespace soiq::render
