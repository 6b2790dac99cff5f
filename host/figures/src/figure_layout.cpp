#include "intgrid/figures/figure_layout.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "intgrid/figures/bitmap_font.hpp"

namespace intgrid::figures {
namespace {

constexpr int kTextScale = 2;
constexpr int kMargin = 16;
constexpr int kPanelGap = 24;  // between panels of a row
constexpr int kRowGap = 20;    // between rows, and around the legend
constexpr int kLabelGap = 6;   // between a label and its image
constexpr io::Rgb kInk{0, 0, 0};
constexpr io::Rgb kPanelFrame{120, 120, 120};

// The probabilities the legend's bar spans and the three it marks.
struct LegendRange {
  double low;
  double high;
  std::array<double, 3> ticks;
};

LegendRange legend_range(io::ProbabilityScale scale) {
  if (scale == io::ProbabilityScale::grey) return {0.0, 1.0, {0.0, 0.5, 1.0}};
  const double s = io::kDivergingSaturation;
  return {0.5 - 1.5 * s, 0.5 + 1.5 * s, {0.5 - s, 0.5, 0.5 + s}};
}

void fill_rect(io::RgbImage& image, int x, int y, int width, int height, io::Rgb color) {
  for (int row = y; row < y + height; ++row)
    for (int column = x; column < x + width; ++column) image.set(column, row, color);
}

void draw_frame(io::RgbImage& image, int x, int y, int width, int height, io::Rgb color) {
  fill_rect(image, x, y, width, 1, color);
  fill_rect(image, x, y + height - 1, width, 1, color);
  fill_rect(image, x, y, 1, height, color);
  fill_rect(image, x + width - 1, y, 1, height, color);
}

// "P(occupied)", the framed bar with its ticks, and a framed swatch of the colour of no cell.
io::RgbImage render_legend(io::ProbabilityScale scale) {
  constexpr int kBarWidth = 300, kBarHeight = 16, kTickLength = 4;
  constexpr int kBoxHeight = kBarHeight + 2;  // with the frame
  const LegendRange range = legend_range(scale);
  const std::string name = "P(occupied)", no_cell = "no cell";
  const TextSize name_size = text_size(name, kTextScale);
  const TextSize no_cell_size = text_size(no_cell, kTextScale);
  const int bar_x = name_size.width + 12;
  const int swatch_x = bar_x + kBarWidth + 40;
  const int tick_label_y = kBoxHeight + kTickLength + 2;
  io::RgbImage legend(swatch_x + kBoxHeight + 8 + no_cell_size.width,
                      tick_label_y + text_size("0", kTextScale).height);
  draw_text(legend, 0, (kBoxHeight - name_size.height) / 2, name, kInk, kTextScale);
  for (int column = 0; column < kBarWidth; ++column) {
    const double p = range.low + (range.high - range.low) * (column + 0.5) / kBarWidth;
    fill_rect(legend, bar_x + column, 1, 1, kBarHeight, io::probability_color(p, scale));
  }
  draw_frame(legend, bar_x - 1, 0, kBarWidth + 2, kBoxHeight, kInk);
  for (const double tick : range.ticks) {
    const int x =
        bar_x +
        static_cast<int>(std::lround((tick - range.low) / (range.high - range.low) * kBarWidth));
    fill_rect(legend, x, kBoxHeight, 1, kTickLength, kInk);
    char label[16];
    std::snprintf(label, sizeof label, "%.2g", tick);
    draw_text(legend, x - text_size(label, kTextScale).width / 2, tick_label_y, label, kInk,
              kTextScale);
  }
  fill_rect(legend, swatch_x, 0, kBoxHeight, kBoxHeight,
            io::probability_color(std::numeric_limits<double>::quiet_NaN(), scale));
  draw_frame(legend, swatch_x, 0, kBoxHeight, kBoxHeight, kInk);
  draw_text(legend, swatch_x + kBoxHeight + 8, (kBoxHeight - no_cell_size.height) / 2, no_cell,
            kInk, kTextScale);
  return legend;
}

struct RowLayout {
  std::vector<int> column_widths;
  int label_height = 0;
  int image_height = 0;
  int width = 0;
  int height() const { return label_height + kLabelGap + image_height; }
};

RowLayout lay_out(const std::vector<Panel>& row) {
  RowLayout layout;
  for (const Panel& panel : row) {
    const TextSize label = text_size(panel.label, kTextScale);
    layout.column_widths.push_back(std::max(panel.image.width, label.width));
    layout.label_height = std::max(layout.label_height, label.height);
    layout.image_height = std::max(layout.image_height, panel.image.height);
    layout.width += layout.column_widths.back() + (layout.column_widths.size() > 1 ? kPanelGap : 0);
  }
  return layout;
}

std::string joined_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += (text.empty() ? "" : "\n") + line;
  return text;
}

}  // namespace

io::RgbImage compose_figure(std::string_view title, const std::vector<std::vector<Panel>>& rows,
                            io::ProbabilityScale scale, const std::vector<std::string>& caption) {
  const TextSize title_size = text_size(title, kTextScale);
  const io::RgbImage legend = render_legend(scale);
  const std::string caption_text = joined_lines(caption);
  const TextSize caption_size = text_size(caption_text, kTextScale);
  std::vector<RowLayout> layouts;
  int content_width = std::max({title_size.width, legend.width, caption_size.width});
  int height = kMargin + title_size.height + kRowGap;
  for (const std::vector<Panel>& row : rows) {
    layouts.push_back(lay_out(row));
    content_width = std::max(content_width, layouts.back().width);
    height += layouts.back().height() + kRowGap;
  }
  height += legend.height + kRowGap + caption_size.height + kMargin;

  io::RgbImage figure(content_width + 2 * kMargin, height);
  int y = kMargin;
  draw_text(figure, kMargin, y, title, kInk, kTextScale);
  y += title_size.height + kRowGap;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    int x = kMargin;
    for (std::size_t p = 0; p < rows[r].size(); ++p) {
      const Panel& panel = rows[r][p];
      const int column_width = layouts[r].column_widths[p];
      draw_text(figure, x + (column_width - text_size(panel.label, kTextScale).width) / 2, y,
                panel.label, kInk, kTextScale);
      const int image_x = x + (column_width - panel.image.width) / 2;
      const int image_y = y + layouts[r].label_height + kLabelGap;
      io::draw_image(figure, panel.image, image_x, image_y);
      draw_frame(figure, image_x - 1, image_y - 1, panel.image.width + 2, panel.image.height + 2,
                 kPanelFrame);
      x += column_width + kPanelGap;
    }
    y += layouts[r].height() + kRowGap;
  }
  io::draw_image(figure, legend, kMargin, y);
  y += legend.height + kRowGap;
  draw_text(figure, kMargin, y, caption_text, kInk, kTextScale);
  return figure;
}

}  // namespace intgrid::figures
