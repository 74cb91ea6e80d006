// A tiny bitmap font for labels drawn on images (plots, side-by-side
// comparisons), so that no font library or external tool is needed.
//
// Every printable ASCII character (32 to 126) is a 5x7 pixel glyph drawn in
// a cell of kCharAdvance x kLineHeight pixels. Capitals and digits fill rows
// 0 to 6; the lower-case letters g, p, q and y hang two rows below the
// others (rows 2 to 8). Characters outside the set are drawn as '?'. The
// glyphs are written out in bitmap_font.cpp, one line each, so they can be
// read and edited by eye.
#pragma once

#include <string>

#include "core/color.h"
#include "image/image.h"

namespace pt {

constexpr int kGlyphWidth = 5;   ///< pixels, at scale 1
constexpr int kGlyphHeight = 7;  ///< pixels above the descender, at scale 1
constexpr int kCharAdvance = 6;  ///< pixels from one character to the next, at scale 1
constexpr int kLineHeight = 10;  ///< pixels from one line to the next, at scale 1

/// Whether `c` has a glyph of its own (otherwise it is drawn as '?').
bool has_glyph(char c);

/// Whether the glyph's pixel (column, row) is set; row 0 is the top of the
/// glyph's own 7 rows (before the descender shift). Out-of-range is false.
bool glyph_pixel(char c, int column, int row);

/// Width in pixels of `text` on one line at `scale` (no trailing space).
int text_width(const std::string& text, int scale = 1);

/// Draws `text` left to right with the top-left corner of its first cell
/// at (x, y), each font pixel a scale x scale square of `color` (linear).
/// Pixels outside the image are skipped.
void draw_text(Image& image, int x, int y, const std::string& text, const Color& color,
               int scale = 1);

/// Draws `text` reading upwards (rotated 90 degrees counter-clockwise), for
/// the label of a vertical axis: the text starts at (x, y) and runs towards
/// smaller y; its cells extend to larger x.
void draw_text_up(Image& image, int x, int y, const std::string& text, const Color& color,
                  int scale = 1);

}  // namespace pt
