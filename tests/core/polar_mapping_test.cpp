// Range mapping of polar ISMs onto a world grid, against a direct polar-coordinate
// classification of every cell centre, and multi-sensor fusion of the mapped grids.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <tuple>

#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/polar_mapping.hpp"
#include "intgrid/kernel/ism_kernel.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;

namespace intgrid {
namespace {

const GridGeometry kWorld{80, 70, 0.05, -1.0, -1.5};

TEST(PolarMapping, EveryCellCentreLandsInItsPolarCell) {
  for (const Pose2 sensor :
       {Pose2{0.0, 0.0, 0.0}, Pose2{0.31, -0.27, 2.1}, Pose2{1.1, 0.4, -2.9}}) {
    const SectoralGrid polar{0.6, 30, 12, 4, 0.05};
    std::set<std::tuple<std::size_t, int, int>> mapped;
    for_each_polar_cell(kWorld, sensor, polar, [&](std::size_t index, int ring, int bin) {
      EXPECT_TRUE(mapped.insert({index, ring, bin}).second) << "visited twice";
    });
    // The oracle: polar coordinates of each centre, cells near a boundary left out.
    std::size_t expected = 0;
    for (int iy = 0; iy < kWorld.height; ++iy)
      for (int ix = 0; ix < kWorld.width; ++ix) {
        const double dx = kWorld.centre_x(ix) - sensor.x, dy = kWorld.centre_y(iy) - sensor.y;
        const double angle =
            std::remainder(std::atan2(dy, dx) - sensor.theta, 2 * std::numbers::pi);
        const double bin_f = (angle + 0.5 * polar.fov) / (polar.fov / polar.bins);
        const double ring_f = std::hypot(dx, dy) / polar.cell;
        const bool near_edge = std::abs(bin_f - std::round(bin_f)) < 1e-9 ||
                               std::abs(ring_f - std::floor(ring_f) - 0.5) < 1e-9;
        const int bin = static_cast<int>(std::floor(bin_f));
        const int ring = static_cast<int>(std::lround(ring_f));
        const bool inside = bin >= 0 && bin < polar.bins && ring >= 1 && ring <= polar.rings;
        if (near_edge) {
          if (inside) ++expected;  // counted, wherever it landed
          continue;
        }
        if (inside) {
          ++expected;
          EXPECT_TRUE(mapped.count({kWorld.index(ix, iy), ring, bin})) << ix << "," << iy;
        }
      }
    EXPECT_EQ(mapped.size(), expected);
  }
}

TEST(PolarMapping, MapsValuesAndLeavesTheRestUnknown) {
  const SectoralGrid polar{0.5, 20, 8, 2, 0.05};
  const Pose2 sensor{0.0, 0.0, 0.3};
  std::vector<double> values(polar.cells());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.001 * double(i + 1);
  const ProbabilityGrid grid = map_polar<double>(kWorld, sensor, polar, values, 0.5);
  std::size_t informed = 0;
  for_each_polar_cell(kWorld, sensor, polar, [&](std::size_t index, int ring, int bin) {
    ++informed;
    EXPECT_EQ(grid.cells[index], values[std::size_t((ring - 1) * polar.bins + bin)]);
  });
  EXPECT_EQ(std::count(grid.cells.begin(), grid.cells.end(), 0.5),
            std::ptrdiff_t(grid.cells.size() - informed));
  EXPECT_THROW(map_polar<double>(kWorld, sensor, polar, std::span(values).first(3), 0.5),
               std::invalid_argument);
}

TEST(PolarMapping, NarrowAndLargeFovSensorsFuse) {
  // Thesis figure 2.13: a narrow beam and a cone look at one obstacle; where one sensor
  // alone informs a cell the fused grid keeps its value, where both do Bayes combines them,
  // and the integer grids (index addition) follow within the quantization budget.
  const SectoralGrid cone{0.5235987755982988, 40, 16, 4, 0.05};
  const SectoralGrid beam{0.035, 40, 1, 1, 0.05};
  const Pose2 a{0.0, 0.0, 0.0}, b{0.0, -0.4, 0.3};
  const ConeSensorModel cone_model;
  const GaussianBeamModel beam_model{0.02, 0.0};
  const std::vector<double> pa = narrow_ism(beam_model, 1.2, beam.cell, 40);
  const std::vector<double> pb = sectoral_ism(cone_model, cone, 1.25);
  // A row of cell centres on the beam's axis, so the narrow footprint holds cells.
  const GridGeometry world{80, 70, 0.05, -1.0, -1.525};
  const ProbabilityGrid ga = map_polar<double>(world, a, beam, pa, 0.5);
  const ProbabilityGrid gb = map_polar<double>(world, b, cone, pb, 0.5);
  const ProbabilityGrid fused = fuse_grids(ga, gb);

  const SepsCodec codec(8, 0.05);
  const IsmKernelTables kernel = make_ism_kernel(cone_model, cone, codec);
  std::vector<std::int8_t> ia(pa.size()), ib(pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i)
    ia[i] = std::int8_t(codec.quantize_conservative(pa[i]));
  const std::vector<std::int16_t> kb = ism_kernel_indices(kernel, quantize_reading(kernel, 1.25));
  const std::vector<double> pb_kernel =
      sectoral_ism(cone_model, cone, reading_metres(kernel, quantize_reading(kernel, 1.25)));
  for (std::size_t i = 0; i < kb.size(); ++i) ib[i] = std::int8_t(kb[i]);
  const Grid<std::int8_t> fa = map_polar<std::int8_t>(world, a, beam, ia, 0);
  const Grid<std::int8_t> fb = map_polar<std::int8_t>(world, b, cone, ib, 0);
  const Grid<std::int8_t> fused_int = fuse_grids(fa, fb, codec.max_index());
  const ProbabilityGrid gb_kernel = map_polar<double>(world, b, cone, pb_kernel, 0.5);

  std::size_t both = 0;
  for (std::size_t i = 0; i < fused.cells.size(); ++i) {
    const bool in_a = ga.cells[i] != 0.5, in_b = gb.cells[i] != 0.5;
    if (in_a && !in_b) {
      EXPECT_DOUBLE_EQ(fused.cells[i], ga.cells[i]);
    }
    if (in_b && !in_a) {
      EXPECT_DOUBLE_EQ(fused.cells[i], gb.cells[i]);
    }
    both += in_a && in_b;
    // Two quantizations, each within one step, the kernel's within one more: the fused
    // index is within three steps of the fused double, unless saturated.
    const double exact = fuse_probabilities(ga.cells[i], gb_kernel.cells[i]);
    const int n = fused_int.cells[i];
    if (std::abs(n) < codec.max_index()) {
      EXPECT_LE(std::abs(logit(exact) - n * codec.lambda()), 3.0 * codec.lambda() + 1e-9) << i;
    }
  }
  EXPECT_GT(both, 5u);
}

}  // namespace
}  // namespace intgrid
