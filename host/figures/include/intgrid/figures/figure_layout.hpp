// Figures for people: labelled panels in rows under a title, with the legend of the colour
// scale and a caption below, drawn with the built-in bitmap font.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "intgrid/io/image_io.hpp"

namespace intgrid::figures {

struct Panel {
  std::string label;  // drawn above the image; '\n' splits lines
  io::RgbImage image;
};

// Rows of panels left to right, each framed and centred under its label; then the legend of scale
// (its colours over the probabilities where they change, and the colour of no cell) and the
// caption lines.
io::RgbImage compose_figure(std::string_view title, const std::vector<std::vector<Panel>>& rows,
                            io::ProbabilityScale scale, const std::vector<std::string>& caption);

}  // namespace intgrid::figures
