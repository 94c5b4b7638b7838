// render/font.h: a tiny built-in 5x7 bitmap font with 2-row descenders for captions, drawn on the
// CPU into an Image.
#pragma once

#include "render/renderer.h"

#include <array>
#include <cstdint>
#include <string>

namespace frontier::render
{

inline constexpr int cGlyphWidth = 5;
inline constexpr int cGlyphBaseline = 7; // rows 0..6 stand on the baseline (capitals, digits)
inline constexpr int cGlyphHeight = 9;   // rows 7..8 are descenders (g j p q y ,)
inline constexpr int cGlyphAdvance = 6;  // glyph plus one column of spacing

// Row r (0 = top, cGlyphBaseline = first row below the baseline) of a glyph as 5 bits, bit 4 = leftmost
// column. Characters without a glyph (outside ASCII letters, digits and . , = - + : / _ ( ) ? ! ' # % [ ] *)
// draw as '?'.
std::array<std::uint8_t, cGlyphHeight> glyph(char c);

// Width in pixels of `text` at the given integer scale.
int textWidth(const std::string& text, int scale);

// Draws `text` with its top-left corner at (x, y), clipped to the image.
void drawText(Image& image, int x, int y, const std::string& text, int scale,
              std::array<std::uint8_t, 3> rgb);

// Rows of an image of this size (from the top) that drawCaption may cover.
int captionRows(int width, int height);

// A caption in the top-left corner: white text on a darkened, semi-transparent band. Text that
// does not fit the width is cut.
void drawCaption(Image& image, const std::string& text);

} // namespace frontier::render
