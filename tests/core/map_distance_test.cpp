// E(d): the distance from a built map's occupied cells to the true map's, against brute force.
#include "intgrid/core/map_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace intgrid::core;

namespace intgrid {
namespace {

// Every built occupied cell against every true occupied cell, by the nearest point of each.
ObstacleDistance brute_force(const ProbabilityGrid& built, double built_threshold,
                             const ProbabilityGrid& truth, double truth_threshold,
                             ObstacleExtent extent) {
  const GridGeometry& b = built.geometry;
  const GridGeometry& t = truth.geometry;
  ObstacleDistance out;
  double sum = 0.0;
  for (int by = 0; by < b.height; ++by)
    for (int bx = 0; bx < b.width; ++bx) {
      if (!(built.at(bx, by) > built_threshold)) continue;
      double best = std::numeric_limits<double>::infinity();
      for (int ty = 0; ty < t.height; ++ty)
        for (int tx = 0; tx < t.width; ++tx)
          if (truth.at(tx, ty) > truth_threshold) {
            // The nearest point of the square: the point clamped into it.
            const double h = extent == ObstacleExtent::cell ? 0.5 * t.resolution : 0.0;
            const double nx = std::clamp(b.centre_x(bx), t.centre_x(tx) - h, t.centre_x(tx) + h);
            const double ny = std::clamp(b.centre_y(by), t.centre_y(ty) - h, t.centre_y(ty) + h);
            best = std::min(best, std::hypot(nx - b.centre_x(bx), ny - b.centre_y(by)));
          }
      sum += best;
      out.max = std::max(out.max, best);
      ++out.cells;
    }
  out.mean = out.cells ? sum / static_cast<double>(out.cells) : std::nan("");
  return out;
}

ProbabilityGrid random_grid(std::mt19937_64& rng, const GridGeometry& g, double occupied_share) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ProbabilityGrid grid(g, 0.0);
  for (double& p : grid.cells) {
    const double u = unit(rng);
    p = u < occupied_share ? 0.5 + 0.5 * unit(rng) : u < 0.98 ? 0.5 * unit(rng) : std::nan("");
  }
  return grid;
}

TEST(MapDistance, EqualsBruteForceOnRandomGridsOfOtherGeometries) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> size(1, 40);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    // Sparse, dense and single-cell truths; built grids coarser, finer, shifted, overhanging.
    const double share = trial % 3 == 0 ? 0.002 : trial % 3 == 1 ? 0.05 : 0.5;
    const GridGeometry tg{size(rng), size(rng), 0.05 + 0.1 * unit(rng), 4.0 * unit(rng) - 2.0,
                          4.0 * unit(rng) - 2.0};
    ProbabilityGrid truth = random_grid(rng, tg, share);
    if (std::none_of(truth.cells.begin(), truth.cells.end(), [](double p) { return p > 0.5; }))
      truth.at(size(rng) % tg.width, size(rng) % tg.height) = 1.0;
    const GridGeometry bg{size(rng), size(rng), 0.03 + 0.2 * unit(rng), 6.0 * unit(rng) - 4.0,
                          6.0 * unit(rng) - 4.0};
    const ProbabilityGrid built = random_grid(rng, bg, 0.3);
    for (const ObstacleExtent extent : {ObstacleExtent::cell, ObstacleExtent::centre}) {
      const ObstacleDistance fast = distance_to_nearest_obstacle(built, 0.5, truth, 0.5, extent);
      const ObstacleDistance slow = brute_force(built, 0.5, truth, 0.5, extent);
      ASSERT_EQ(fast.cells, slow.cells);
      if (slow.cells == 0) {
        EXPECT_TRUE(std::isnan(fast.mean));
        continue;
      }
      EXPECT_NEAR(fast.mean, slow.mean, 1e-12);
      EXPECT_NEAR(fast.max, slow.max, 1e-12);
      EXPECT_DOUBLE_EQ(mean_distance_to_nearest_obstacle(built, 0.5, truth, 0.5, extent),
                       fast.mean);
    }
  }
}

TEST(MapDistance, SameGridIsZeroAndAShiftIsItsLength) {
  const GridGeometry g{30, 20, 0.1, -1.0, 2.0};
  ProbabilityGrid truth(g, 0.0);
  for (int x = 3; x < 27; ++x) truth.at(x, 10) = 1.0;  // a wall along y = 3.05
  EXPECT_EQ(mean_distance_to_nearest_obstacle(truth, 0.5, truth, 0.5), 0.0);
  // The same wall built 3 cells higher: every built centre is 0.3 m from the true centres and
  // 0.25 m from the wall's edge.
  ProbabilityGrid built(g, 0.0);
  for (int x = 3; x < 27; ++x) built.at(x, 13) = 0.9;
  ObstacleDistance d = distance_to_nearest_obstacle(built, 0.5, truth, 0.5, ObstacleExtent::centre);
  EXPECT_EQ(d.cells, 24u);
  EXPECT_NEAR(d.mean, 0.3, 1e-12);
  EXPECT_NEAR(d.max, 0.3, 1e-12);
  d = distance_to_nearest_obstacle(built, 0.5, truth, 0.5);
  EXPECT_NEAR(d.mean, 0.25, 1e-12);
  EXPECT_NEAR(d.max, 0.25, 1e-12);
  // Thresholds are strict: a built cell at exactly the threshold is not occupied.
  built.at(0, 0) = 0.5;
  EXPECT_EQ(distance_to_nearest_obstacle(built, 0.5, truth, 0.5).cells, 24u);
}

// A perfect map on a grid offset by half a cell in x and y, as a SLAM map centred on a pose at a
// cell corner: 0 to the cells' squares, resolution / sqrt(2) to their centres.
TEST(MapDistance, HalfACellOffsetIsZeroToSquaresAndAHalfDiagonalToCentres) {
  ProbabilityGrid truth({20, 20, 0.1, 0.0, 0.0}, 0.0);
  for (int i = 0; i < 20; ++i) truth.at(i, 10) = truth.at(10, i) = 1.0;
  ProbabilityGrid built({21, 21, 0.1, -0.05, -0.05}, 0.0);
  // Centres at multiples of 0.1: on the edges of the true cells (the walls x, y in [1, 1.1]).
  for (int i = 0; i < 21; ++i) built.at(i, 11) = built.at(11, i) = 1.0;
  EXPECT_NEAR(mean_distance_to_nearest_obstacle(built, 0.5, truth, 0.5), 0.0, 1e-12);
  const ObstacleDistance d =
      distance_to_nearest_obstacle(built, 0.5, truth, 0.5, ObstacleExtent::centre);
  EXPECT_NEAR(d.max, std::hypot(0.05, 0.05), 1e-12);
}

TEST(MapDistance, FarOutsideTheTrueMapIsMeasuredToo) {
  ProbabilityGrid truth({10, 10, 0.1, 0.0, 0.0}, 0.0);
  truth.at(9, 9) = 1.0;                                // centre (0.95, 0.95)
  ProbabilityGrid built({1, 1, 0.1, 10.9, 0.9}, 1.0);  // centre (10.95, 0.95)
  EXPECT_NEAR(mean_distance_to_nearest_obstacle(built, 0.5, truth, 0.5, ObstacleExtent::centre),
              10.0, 1e-12);
  EXPECT_NEAR(mean_distance_to_nearest_obstacle(built, 0.5, truth, 0.5), 9.95, 1e-12);
}

TEST(MapDistance, NoBuiltObstacleIsNanAndNoTrueObstacleThrows) {
  const ProbabilityGrid empty({5, 5, 0.1, 0.0, 0.0}, 0.2);
  ProbabilityGrid truth = empty;
  truth.at(2, 2) = 1.0;
  const ObstacleDistance d = distance_to_nearest_obstacle(empty, 0.5, truth, 0.5);
  EXPECT_EQ(d.cells, 0u);
  EXPECT_TRUE(std::isnan(d.mean));
  EXPECT_THROW(distance_to_nearest_obstacle(truth, 0.5, empty, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
