// A small built-in bitmap font for the labels of figures, so that pictures need no font
// library: 5 x 8 pixel glyphs (7 rows above the baseline, one below for descenders) for
// printable ASCII.
#pragma once

#include <string_view>

#include "intgrid/io/image_io.hpp"

namespace intgrid::figures {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 8;
inline constexpr int kGlyphAdvance = kGlyphWidth + 1;  // one column between characters
inline constexpr int kLineAdvance = kGlyphHeight + 2;  // two rows between lines

struct TextSize {
  int width = 0;
  int height = 0;
};

// The box draw_text can touch: lines split at '\n', each font pixel a scale x scale block.
// Throws std::invalid_argument unless scale >= 1.
TextSize text_size(std::string_view text, int scale = 1);

// Draws text with the top-left corner of its box at (x, y_from_top), clipped to the image.
// Characters outside printable ASCII draw as '?'. Throws std::invalid_argument unless
// scale >= 1.
void draw_text(io::RgbImage& image, int x, int y_from_top, std::string_view text, io::Rgb color,
               int scale = 1);

}  // namespace intgrid::figures
