// The grid SLAM's motion: the pose grid's mean follows the composed odometry.
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
// 3. Motion update: scans without usable readings only move Pi.

struct MotionTrace {
  std::vector<Pose2> expected;  // the composed odometry, SLAM frame
  std::vector<SlamEstimate> estimates;
  std::vector<double> mass;
};

GridSlamConfig motion_config() {
  GridSlamConfig c = small_config();
  c.motion.xy0 = 0.03;  // a kernel of at least 0.3 cells: its sampled mean is its centre
  c.window.headings = 31;
  return c;
}

// Odometry increments (robot frame) of a curving path.
std::vector<Pose2> motion_increments() {
  std::vector<Pose2> u;
  for (int i = 0; i < 12; ++i)
    u.push_back({0.2 + 0.013 * (i % 5), 0.02 * ((i % 3) - 1), i < 6 ? 0.05 : -0.08});
  return u;
}

template <class Pr>
MotionTrace run_motion_only() {
  const GridSlamConfig config = motion_config();
  Log log;
  Pose2 pose{1.0, 2.0, -0.7};  // the first pose, in the log's frame
  const Pose2 first = pose;
  std::vector<Pose2> poses{pose};
  for (const Pose2& u : motion_increments()) poses.push_back(pose = compose(pose, u));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Scan s = make_scan(World{}, {}, poses[i], 0.1 * static_cast<double>(i), 36);
    std::fill(s.ranges.begin(), s.ranges.end(), 0.0);
    log.scans.push_back(s);
  }
  const std::vector<QuantizedScan> scans = quantize(log, config);
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 4.0);
  GridSlamEngine<Pr> slam(setup, make_probabilities<Pr>(setup));
  MotionTrace trace;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    slam.process(scans[i]);
    trace.expected.push_back(relative(first, poses[i]));
    trace.estimates.push_back(slam.estimate());
    trace.mass.push_back(mass(slam));
  }
  EXPECT_EQ(slam.skipped_scans(), scans.size());
  EXPECT_EQ(slam.mappings(), 0u);
  EXPECT_EQ(slam.localizations(), 0u);
  EXPECT_TRUE(std::all_of(slam.map().cells.begin(), slam.map().cells.end(),
                          [](std::int8_t n) { return n == 0; }));
  return trace;
}

template <class Pr>
void expect_mean_follows_odometry(const char* name) {
  const MotionTrace t = run_motion_only<Pr>();
  const GridSlamConfig c = motion_config();
  const double bin = 2.0 * kPi / c.headings;
  double worst_xy = 0.0, worst_theta = 0.0, worst_mass = 0.0;
  for (std::size_t i = 0; i < t.estimates.size(); ++i) {
    const Pose2 e = pose_of(t.estimates[i]);
    const double dxy = std::hypot(e.x - t.expected[i].x, e.y - t.expected[i].y);
    const double dth = std::abs(wrap(e.theta - t.expected[i].theta));
    worst_xy = std::max(worst_xy, dxy);
    worst_theta = std::max(worst_theta, dth);
    worst_mass = std::max(worst_mass, std::abs(t.mass[i] - 1.0));
    EXPECT_LE(dxy, 0.5 * c.cell) << name << " step " << i;
    EXPECT_LE(dth, bin) << name << " step " << i;
    if (i > 0) {
      // The spread grows with every motion.
      EXPECT_GT(t.estimates[i].sigma_um, t.estimates[i - 1].sigma_um) << name << " step " << i;
    }
  }
  EXPECT_EQ(t.estimates[0].sigma_um, 0);
  // After 12 steps of ~0.2 m the spread is that of a random walk, some 0.05 m a step: between
  // 0.1 and 0.3 m.
  EXPECT_GT(t.estimates.back().sigma_um, 100000) << name;
  EXPECT_LT(t.estimates.back().sigma_um, 300000) << name;
  if constexpr (std::is_same_v<Pr, DoubleProbabilities>) {
    EXPECT_LE(worst_mass, 1e-12);
  } else {
    // Normalizing divides by the pairwise sum of the grid, exact in U_gamma; that sum rounds
    // by half a step per level of the pairwise tree, so the mass is 1 within gamma^(-+d/2).
    const double steps = 0.5 * pairwise_depth(static_cast<std::size_t>(c.window.cells) *
                                              static_cast<std::size_t>(c.window.cells) *
                                              static_cast<std::size_t>(c.window.headings));
    EXPECT_LE(worst_mass, std::exp2(steps / c.ugamma.steps_per_halving) - 1.0);
  }
  std::printf(
      "[slam] motion only, %s: worst mean error %.4f m (bound %.3f), %.5f rad (bound %.5f); "
      "final sigma %.4f m; worst |mass - 1| %.3g\n",
      name, worst_xy, 0.5 * c.cell, worst_theta, bin,
      static_cast<double>(t.estimates.back().sigma_um) * 1e-6, worst_mass);
}

TEST(SlamMotion, MeanFollowsTheComposedOdometryInDouble) {
  expect_mean_follows_odometry<DoubleProbabilities>("double");
}

TEST(SlamMotion, MeanFollowsTheComposedOdometryInInteger) {
  expect_mean_follows_odometry<IndexProbabilities>("integer");
}

TEST(SlamMotion, IntegerAndDoubleMeansAgree) {
  const MotionTrace d = run_motion_only<DoubleProbabilities>();
  const MotionTrace n = run_motion_only<IndexProbabilities>();
  ASSERT_EQ(d.estimates.size(), n.estimates.size());
  double worst_xy = 0.0, worst_theta = 0.0, worst_sigma = 0.0;
  for (std::size_t i = 0; i < d.estimates.size(); ++i) {
    const Pose2 a = pose_of(d.estimates[i]), b = pose_of(n.estimates[i]);
    worst_xy = std::max(worst_xy, std::hypot(a.x - b.x, a.y - b.y));
    worst_theta = std::max(worst_theta, std::abs(a.theta - b.theta));
    if (i > 0)
      worst_sigma =
          std::max(worst_sigma, std::abs(static_cast<double>(n.estimates[i].sigma_um) /
                                             static_cast<double>(d.estimates[i].sigma_um) -
                                         1.0));
  }
  EXPECT_LE(worst_xy, 0.01);
  EXPECT_LE(worst_theta, 0.002);
  EXPECT_LE(worst_sigma, 0.05);
  std::printf(
      "[slam] motion only, integer vs double: worst mean gap %.5f m, %.6f rad, sigma %.2f%%\n",
      worst_xy, worst_theta, 100.0 * worst_sigma);
}

TEST(SlamMotion, WindowReachingTheMapEdgeThrows) {
  GridSlamConfig config = small_config();
  config.sensor.max_range = 1.0;
  config.map.margin = 1.0;
  const SlamSetup setup = make_slam_setup(config, make_scan(World{}, {}, {}, 0.0, 36), 0.0);
  GridSlamEngine<DoubleProbabilities> slam(setup, make_probabilities<DoubleProbabilities>(setup));
  QuantizedScan scan;
  scan.range_mm.assign(36, 0);
  ASSERT_NO_THROW(slam.process(scan));
  scan.odom_dx_mm = 500;
  try {
    for (int i = 0; i < 100; ++i) slam.process(scan);
    ADD_FAILURE() << "drove off the map without an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("edge of the map"), std::string::npos) << e.what();
  }
}

// make_slam_setup's contract: a map for a run whose odometry stays within reach_m of the first
// pose, plus max_range, plus map_margin. With no margin the run must still fit while the
// robot stays within that reach.
TEST(SlamMotion, RunWithinTheAnnouncedReachFitsTheMapWithoutMargin) {
  for (const double max_range : {1.0, 10.0}) {
    GridSlamConfig config = small_config();
    config.sensor.max_range = max_range;
    config.map.margin = 0.0;
    const double reach = 2.0;
    const SlamSetup setup = make_slam_setup(config, make_scan(World{}, {}, {}, 0.0, 36), reach);
    GridSlamEngine<DoubleProbabilities> slam(setup, make_probabilities<DoubleProbabilities>(setup));
    QuantizedScan scan;
    scan.range_mm.assign(36, 0);
    int done = 0;
    try {
      for (; done <= 10; ++done) {
        slam.process(scan);
        scan.odom_dx_mm = 200;  // ten steps of 0.2 m: exactly the reach
      }
    } catch (const std::runtime_error& e) {
      ADD_FAILURE() << "max range " << max_range << ": threw at step " << done << " of 10, "
                    << static_cast<double>(slam.estimate().x_um) * 1e-6
                    << " m from the start (reach " << reach << " m; map " << setup.origin_cell_x
                    << " cells each side): " << e.what();
    }
  }
}

// The integer estimate of a broad pose grid: weights up to 2^20 times sums of squared window
// indices, over a large window, in 64 bits. The double estimate is the oracle.
TEST(SlamMotion, IntegerEstimateOfABroadPoseGridOnALargeWindow) {
  struct Window {
    int cells, headings;
  };
  for (const Window w : {Window{161, 1}, Window{61, 61}}) {
    GridSlamConfig config = small_config();
    config.window.cells = w.cells;
    config.window.headings = w.headings;
    config.motion.xy0 = 5.0;  // one update spreads Pi nearly evenly over the window
    config.motion.theta0 = 2.0;
    config.sensor.max_range = 1.0;
    config.map.margin = 10.0;
    const SlamSetup setup = make_slam_setup(config, make_scan(World{}, {}, {}, 0.0, 36), 0.0);
    GridSlamEngine<DoubleProbabilities> d(setup, make_probabilities<DoubleProbabilities>(setup));
    GridSlamEngine<IndexProbabilities> n(setup, make_probabilities<IndexProbabilities>(setup));
    QuantizedScan scan;
    scan.range_mm.assign(36, 0);
    for (int i = 0; i < 2; ++i) {  // the second scan's motion update
      d.process(scan);
      n.process(scan);
    }
    const double sd = static_cast<double>(d.estimate().sigma_um) * 1e-6;
    const double sn = static_cast<double>(n.estimate().sigma_um) * 1e-6;
    std::printf(
        "[slam] broad pose grid, %d cells x %d headings: sigma double %.4f m, integer %.4f m\n",
        w.cells, w.headings, sd, sn);
    EXPECT_GT(sd, 1.0) << w.cells;
    EXPECT_NEAR(sn, sd, 0.05 * sd) << w.cells << " x " << w.headings;
    EXPECT_NEAR(static_cast<double>(n.estimate().x_um) * 1e-6,
                static_cast<double>(d.estimate().x_um) * 1e-6, 0.05);
    EXPECT_NEAR(static_cast<double>(n.estimate().y_um) * 1e-6,
                static_cast<double>(d.estimate().y_um) * 1e-6, 0.05);
    EXPECT_NEAR(static_cast<double>(n.estimate().theta_q8) / 256.0 * kUnit,
                static_cast<double>(d.estimate().theta_q8) / 256.0 * kUnit, 0.01);
  }
}

}  // namespace
}  // namespace intgrid
