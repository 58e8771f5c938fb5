// bitmap_font.h — a small built-in bitmap font for the labels of false-colour pictures (there is
// no font library): hand-made glyphs 5 pixels wide on 9 rows (7 above the baseline, capitals and
// digits; 2 below it, descenders), drawn scaled by a whole factor.
//
// Covered: the digits, a-z, A-Z, space and . , - + % / : ( ) = _ ? ' ! ² °. Text is UTF-8; any
// other character, and any malformed byte, is drawn as a hollow box, so a label never loses its
// length or crashes. Every character advances 6 columns (5 + 1 of space), times the scale.
#pragma once

#include <string>

#include "io/raster.h"

namespace fen {

constexpr int kGlyphColumns = 5, kGlyphRows = 9, kGlyphAscent = 7, kGlyphAdvance = 6;

// Whether code point `c` has a glyph of its own (not the box).
bool hasGlyph(char32_t c);
// Whether pixel (column, row) of c's glyph is set, 0 <= column < 5, 0 <= row < 9; the box's for
// a character without a glyph.
bool glyphPixel(char32_t c, int column, int row);
// Width in pixels of `text` drawn at `scale` (no trailing space); 0 for "".
int textWidth(const std::string& text, int scale);
// Draws `text` with its first glyph's top-left corner (row 0, the capitals' top) at (x, y).
void drawText(Raster& raster, int x, int y, const std::string& text, Rgb8 color, int scale);

}  // namespace fen
