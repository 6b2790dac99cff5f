// The grid SLAM on a 40-scan loop with a biased odometry, in both arithmetics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/probabilities.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

using namespace intgrid::core;

#include "grid_slam_world.hpp"

namespace intgrid {
namespace {

using namespace intgrid::grid_slam_test;

// ---------------------------------------------------------------------------------------------
// 5, 6. A loop in the room, with a biased and noisy odometry.

TEST(SlamLoop, BothArithmeticsTrackTheLoopFarBetterThanOdometry) {
  const LoopLog& l = loop_log();
  const TrajectoryError odom = absolute_trajectory_error(scan_poses(l.log), l.truth);
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const SlamRun& run = loop_run(a);
    const char* name = a == Arithmetic::integer ? "integer" : "double";
    ASSERT_EQ(run.trajectory.size(), l.log.scans.size());
    EXPECT_EQ(run.scans, 40u);
    EXPECT_EQ(run.mappings, 40u);
    EXPECT_EQ(run.localizations, 39u);
    EXPECT_EQ(run.skipped_scans, 0u);
    EXPECT_EQ(run.readings, 40u * 90u);
    EXPECT_EQ(run.unusable_readings, 0u);
    const TrajectoryError e = absolute_trajectory_error(run.trajectory, l.truth);
    EXPECT_EQ(e.matched, 40u);
    // Pi's hypotheses sit at cell centres and the posterior is nearly one cell, so the error is
    // that of rounding the position to a cell: uniform over a cell, RMS c / sqrt(6) = 0.041 m,
    // at most c / sqrt(2) = 0.071 m (measured: 0.0395 and 0.054 m, both arithmetics).
    const double c = loop_config().cell;
    EXPECT_LT(e.rmse, 1.5 * c / std::sqrt(6.0)) << name;
    EXPECT_LT(e.max, c / std::sqrt(2.0) + 0.01) << name;
    EXPECT_LT(e.mean_heading, 0.03) << name;
    EXPECT_LT(e.rmse, 0.25 * odom.rmse) << name;
    EXPECT_GT(run.mean_sigma(), 0.0);
    EXPECT_LT(run.mean_sigma(), 0.1);
    std::printf(
        "[slam] loop, %s: ATE rmse %.4f m, max %.4f m, mean heading error %.4f rad, E(sigma) "
        "%.4f m; odometry ATE rmse %.4f m, max %.4f m, heading %.4f rad\n",
        name, e.rmse, e.max, e.mean_heading, run.mean_sigma(), odom.rmse, odom.max,
        odom.mean_heading);
  }
  ASSERT_GT(odom.rmse, 0.2);  // the test would not show anything with a good odometry
}

TEST(SlamLoop, IntegerAndDoubleTrajectoriesAgree) {
  const SlamRun& d = loop_run(Arithmetic::floating);
  const SlamRun& n = loop_run(Arithmetic::integer);
  const TrajectoryError gap = absolute_trajectory_error(n.trajectory, d.trajectory);
  EXPECT_LT(gap.rmse, 0.05);
  EXPECT_LT(gap.mean_heading, 0.02);
  // The maps agree on most cells' sign.
  ASSERT_EQ(d.map.cells.size(), n.map.cells.size());
  std::size_t touched = 0, agree = 0;
  for (std::size_t i = 0; i < d.map.cells.size(); ++i) {
    if (d.map.cells[i] == 0 && n.map.cells[i] == 0) continue;
    ++touched;
    agree += (d.map.cells[i] > 0) == (n.map.cells[i] > 0);
  }
  EXPECT_GT(static_cast<double>(agree), 0.95 * static_cast<double>(touched));
  std::printf(
      "[slam] loop, integer vs double: trajectory gap rmse %.4f m, max %.4f m, heading %.4f "
      "rad; map sign agreement %.2f%% of %zu cells\n",
      gap.rmse, gap.max, gap.mean_heading,
      100.0 * static_cast<double>(agree) / static_cast<double>(touched), touched);
}

TEST(SlamLoop, MapShowsTheWallsAndTheFreeSpaceInTheLogFrame) {
  const World world = room_with_pillar();
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const char* name = a == Arithmetic::integer ? "integer" : "double";
    const ProbabilityGrid map = slam_map_probabilities(loop_run(a));
    const GridGeometry& g = map.geometry;
    const double c = g.resolution;
    const auto p = [&](double x, double y) {
      const int ix = g.cell_x(x), iy = g.cell_y(y);
      return g.contains(ix, iy) ? map.at(ix, iy) : 0.5;
    };
    // Along every wall, some cell within one cell of it is occupied.
    std::size_t wall_points = 0, wall_hits = 0;
    const auto on_wall = [&](double x, double y) {
      double best = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) best = std::max(best, p(x + dx * c, y + dy * c));
      ++wall_points;
      wall_hits += best > 0.5;
    };
    for (double s = -2.7; s <= 2.7; s += 0.1) {
      on_wall(s, -3.0);
      on_wall(s, 3.0);
      on_wall(-3.0, s);
      on_wall(3.0, s);
    }
    // Free space: more than 3 cells from every surface, inside the room.
    std::size_t free_points = 0, free_hits = 0, outside_points = 0, outside_unknown = 0;
    for (double y = -2.95; y < 3.0; y += 0.1)
      for (double x = -2.95; x < 3.0; x += 0.1) {
        if (world.clearance(x, y) <= 3 * c) continue;
        bool in_pillar = false;
        for (const Box& b : world.pillars)
          in_pillar = in_pillar || (x > b.x0 && x < b.x1 && y > b.y0 && y < b.y1);
        if (in_pillar) continue;
        ++free_points;
        free_hits += p(x, y) < 0.5;
      }
    // Outside the room, more than 3 cells from it: never seen.
    for (double y = -4.0; y <= 4.0; y += 0.1)
      for (double x = -4.0; x <= 4.0; x += 0.1) {
        if (world.inside_room(x, y, 3 * c)) continue;
        ++outside_points;
        outside_unknown += p(x, y) == 0.5;
      }
    EXPECT_GT(static_cast<double>(wall_hits), 0.97 * static_cast<double>(wall_points)) << name;
    EXPECT_GT(static_cast<double>(free_hits), 0.97 * static_cast<double>(free_points)) << name;
    EXPECT_EQ(outside_unknown, outside_points) << name;
    std::printf(
        "[slam] loop map, %s: walls occupied at %zu/%zu points, free space empty at %zu/%zu, "
        "outside unknown at %zu/%zu\n",
        name, wall_hits, wall_points, free_hits, free_points, outside_unknown, outside_points);
  }
}

TEST(SlamLoop, RunsAreBitIdentical) {
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const SlamRun& first = loop_run(a);
    const SlamRun again = run_grid_slam(loop_log().log, loop_config(), a);
    ASSERT_EQ(again.trajectory.size(), first.trajectory.size());
    for (std::size_t i = 0; i < first.trajectory.size(); ++i) {
      // Bit-identical doubles: compare with ==, no tolerance.
      EXPECT_EQ(again.trajectory[i].t, first.trajectory[i].t);
      EXPECT_EQ(again.trajectory[i].pose.x, first.trajectory[i].pose.x) << i;
      EXPECT_EQ(again.trajectory[i].pose.y, first.trajectory[i].pose.y) << i;
      EXPECT_EQ(again.trajectory[i].pose.theta, first.trajectory[i].pose.theta) << i;
      EXPECT_EQ(again.sigma[i], first.sigma[i]) << i;
    }
    EXPECT_EQ(again.map.cells, first.map.cells);
    EXPECT_EQ(again.map.geometry.width, first.map.geometry.width);
    EXPECT_EQ(again.map.geometry.origin_x, first.map.geometry.origin_x);
  }
}

}  // namespace
}  // namespace intgrid
