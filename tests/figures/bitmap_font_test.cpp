// The built-in bitmap font: text sizes, and drawing that stays inside the text's box.
#include "intgrid/figures/bitmap_font.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace intgrid::io;

using namespace intgrid::core;

using namespace intgrid::figures;

namespace intgrid {
namespace {

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kInk{0, 0, 0};

bool is_white(const RgbImage& image, int x, int y) {
  const Rgb c = image.get(x, y);
  return c.r == 255 && c.g == 255 && c.b == 255;
}

int inked_pixels(const RgbImage& image) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) count += is_white(image, x, y) ? 0 : 1;
  return count;
}

RgbImage drawn(const std::string& text, int scale = 1) {
  RgbImage image(120, 60, kWhite);
  draw_text(image, 0, 0, text, kInk, scale);
  return image;
}

TEST(TextSize, CountsGlyphsLinesAndScale) {
  EXPECT_EQ(text_size("A").width, kGlyphWidth);
  EXPECT_EQ(text_size("A").height, kGlyphHeight);
  EXPECT_EQ(text_size("AB").width, kGlyphAdvance + kGlyphWidth);
  const TextSize two_lines = text_size("AB\nC", 3);
  EXPECT_EQ(two_lines.width, 3 * (kGlyphAdvance + kGlyphWidth));
  EXPECT_EQ(two_lines.height, 3 * (kLineAdvance + kGlyphHeight));
  EXPECT_EQ(text_size("").width, 0);
  EXPECT_EQ(text_size("").height, 0);
  EXPECT_THROW(text_size("A", 0), std::invalid_argument);
}

TEST(DrawText, InksOnlyInsideTheTextBox) {
  for (const std::string text : {"Ns = A = 30", "gjpqy|_~", "P(occupied)\n0.4 0.5", "@#%&"}) {
    for (const int scale : {1, 2, 3}) {
      constexpr int x = 7, y = 5;
      io::RgbImage image(200, 120, kWhite);
      draw_text(image, x, y, text, kInk, scale);
      const TextSize box = text_size(text, scale);
      int inside = 0;
      for (int row = 0; row < image.height; ++row) {
        for (int column = 0; column < image.width; ++column) {
          if (is_white(image, column, row)) continue;
          const bool in_box =
              column >= x && column < x + box.width && row >= y && row < y + box.height;
          EXPECT_TRUE(in_box) << text << " scale " << scale << " at " << column << "," << row;
          ++inside;
        }
      }
      EXPECT_GT(inside, 0) << text;
    }
  }
}

TEST(DrawText, SpaceDrawsNothingAndEveryOtherCharacterSomething) {
  EXPECT_EQ(inked_pixels(drawn(" ")), 0);
  for (char c = '!'; c <= '~'; ++c) EXPECT_GT(inked_pixels(drawn(std::string(1, c))), 0) << c;
}

TEST(DrawText, PrintableCharactersHaveDistinctGlyphs) {
  std::set<std::string> glyphs;
  for (char c = ' '; c <= '~'; ++c) {
    const RgbImage image = drawn(std::string(1, c));
    glyphs.emplace(image.rgb.begin(), image.rgb.end());
  }
  EXPECT_EQ(glyphs.size(), static_cast<std::size_t>('~' - ' ' + 1));
}

TEST(DrawText, UnprintableCharactersDrawAsQuestionMarks) {
  EXPECT_EQ(drawn("\x01\x7f\xe9").rgb, drawn("???").rgb);
}

TEST(DrawText, ScaleMagnifiesEachFontPixel) {
  const RgbImage small = drawn("Ag", 1), large = drawn("Ag", 2);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 60; ++x)
      EXPECT_EQ(is_white(large, x, y), is_white(small, x / 2, y / 2)) << x << "," << y;
}

TEST(DrawText, ClipsAtTheImageBorder) {
  io::RgbImage image(10, 6, kWhite);
  draw_text(image, -3, -4, "WW", kInk, 2);
  draw_text(image, 8, 4, "WW", kInk, 2);
  EXPECT_GT(inked_pixels(image), 0);
  EXPECT_THROW(draw_text(image, 0, 0, "A", kInk, 0), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
