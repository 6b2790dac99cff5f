// Pictures and tables of polar grids, probability colours and figure composition.
#include "intgrid/figures/polar_render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "intgrid/figures/figure_layout.hpp"
#include "intgrid/io/image_io.hpp"

using namespace intgrid::core;

using namespace intgrid::io;
using namespace intgrid::figures;

namespace intgrid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool same(Rgb a, Rgb b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}

TEST(ProbabilityColor, DivergingIsWhiteAtOneHalfAndSaturates) {
  const auto color = [](double p) { return probability_color(p, ProbabilityScale::diverging); };
  EXPECT_TRUE(same(color(0.5), {255, 255, 255}));
  EXPECT_TRUE(same(color(0.5 - kDivergingSaturation), color(0.0)));
  EXPECT_TRUE(same(color(0.5 + kDivergingSaturation), color(1.0)));
  EXPECT_GT(color(0.0).b, color(0.0).r);  // free is blue
  EXPECT_GT(color(1.0).r, color(1.0).b);  // occupied is red
  EXPECT_FALSE(same(color(0.45), color(0.5)));
}

TEST(ProbabilityColor, NoCellHasAColourNoProbabilityHas) {
  for (const ProbabilityScale scale : {ProbabilityScale::grey, ProbabilityScale::diverging}) {
    const Rgb background = probability_color(kNaN, scale);
    for (int i = 0; i <= 1000; ++i)
      EXPECT_FALSE(same(probability_color(i / 1000.0, scale), background)) << i;
  }
  EXPECT_TRUE(same(probability_color(1.0, ProbabilityScale::grey), {0, 0, 0}));
}

TEST(RenderProbabilityGrid, PixelsPerCellMagnifiesEachCell) {
  ProbabilityGrid grid({2, 1, 1.0, 0.0, 0.0}, 0.0);
  grid.at(1, 0) = 1.0;
  const RgbImage image = render_probability_grid(grid, ProbabilityScale::grey, 3);
  ASSERT_EQ(image.width, 6);
  ASSERT_EQ(image.height, 3);
  EXPECT_TRUE(same(image.get(2, 2), {255, 255, 255}));
  EXPECT_TRUE(same(image.get(3, 0), {0, 0, 0}));
  EXPECT_THROW(render_probability_grid(grid, ProbabilityScale::grey, 0), std::invalid_argument);
}

// One 10-degree bin of 4 rings of 1 m, one pixel a centimetre.
const SectoralGrid kBeam{radians(10.0), 4, 1, 1, 1.0};

TEST(RenderPolar, SensorAtTheBottomCentreLookingUp) {
  const PolarFrame frame = polar_frame(kBeam, 0.01);
  const std::vector<double> values{0.1, 0.3, 0.7, 0.9};
  const RgbImage image = render_polar(frame, kBeam, values, ProbabilityScale::grey);
  ASSERT_EQ(image.width, frame.geometry.width);
  ASSERT_EQ(image.height, frame.geometry.height);
  const int axis = frame.geometry.cell_x(frame.sensor.x);
  EXPECT_NEAR(axis, image.width / 2, 1);
  for (int ring = 1; ring <= 4; ++ring) {
    const int row = image.height - 1 - frame.geometry.cell_y(frame.sensor.y + ring * 1.0);
    EXPECT_TRUE(
        same(image.get(axis, row), probability_color(values[ring - 1], ProbabilityScale::grey)))
        << ring;
  }
  const Rgb background = probability_color(kNaN, ProbabilityScale::grey);
  EXPECT_TRUE(same(image.get(0, image.height - 1), background));
  EXPECT_TRUE(same(image.get(image.width - 1, image.height - 1), background));
  EXPECT_TRUE(same(image.get(axis, image.height - 1), background));  // before ring 1
}

TEST(RenderPolar, RefusesValuesOfAnotherGrid) {
  const PolarFrame frame = polar_frame(kBeam, 0.01);
  EXPECT_THROW(render_polar(frame, kBeam, std::vector<double>(3, 0.5), ProbabilityScale::grey),
               std::invalid_argument);
  EXPECT_THROW(polar_frame(kBeam, 0.0), std::invalid_argument);
  EXPECT_THROW(polar_frame(kBeam, 1e-7), std::invalid_argument);  // too many pixels
}

TEST(PolarCsv, OneRowPerCellRingMajorOneBased) {
  SectoralGrid grid = kBeam;
  grid.rings = 2;
  grid.bins = 2;
  std::ostringstream csv;
  write_polar_csv_rows(csv, "7,", grid, std::vector<double>{0.25, 0.5, 0.75, 0.1},
                       std::vector<std::int16_t>{-3, 0, 4, -12});
  EXPECT_EQ(csv.str(), "7,1,1,0.25,-3\n7,1,2,0.5,0\n7,2,1,0.75,4\n7,2,2,0.10000000000000001,-12\n");
  std::ostringstream plain;
  write_polar_csv_rows(plain, "", grid, std::vector<double>{0.25, 0.5, 0.75, 0.1});
  EXPECT_EQ(plain.str().substr(0, 9), "1,1,0.25\n");
  EXPECT_THROW(write_polar_csv_rows(plain, "", grid, std::vector<double>{0.5}),
               std::invalid_argument);
}

TEST(ComposeFigure, HoldsEveryPanelWhole) {
  constexpr Rgb kGreen{0, 255, 0};
  std::vector<Panel> row{{"one", RgbImage(10, 10, kGreen)}, {"two\nlines", RgbImage(4, 7, kGreen)}};
  const RgbImage figure =
      compose_figure("title", {row, {row[0]}}, ProbabilityScale::diverging, {"caption"});
  int green = 0;
  for (int y = 0; y < figure.height; ++y)
    for (int x = 0; x < figure.width; ++x) green += same(figure.get(x, y), kGreen) ? 1 : 0;
  EXPECT_EQ(green, 100 + 28 + 100);
}

}  // namespace
}  // namespace intgrid
