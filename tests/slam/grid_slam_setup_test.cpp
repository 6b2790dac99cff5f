// The grid SLAM's set-up: the sine table, the sensor in integer units, the map origin, the ISM
// table, the config check.
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
// 1. Set-up.

TEST(SlamSetup, SineTableIsWithinOneStepOfStdSin) {
  const World world;
  const SlamSetup s = make_slam_setup(small_config(), make_scan(world, {}, {}, 0.0, 90), 1.0);
  ASSERT_EQ(s.sin_q16.size(), static_cast<std::size_t>(kAngleUnitsPerTurn));
  double worst = 0.0;
  for (int a = 0; a < kAngleUnitsPerTurn; ++a) {
    const double exact = std::sin(2.0 * kPi * a / kAngleUnitsPerTurn);
    const double err = std::abs(s.sin_q16[static_cast<std::size_t>(a)] / 65536.0 - exact);
    worst = std::max(worst, err);
    ASSERT_LE(err, 1.0 / 65536.0) << a;
  }
  // Exact where sin is: 0, 1, -1.
  EXPECT_EQ(s.sin_q16[0], 0);
  EXPECT_EQ(s.sin_q16[16384], 65536);
  EXPECT_EQ(s.sin_q16[32768], 0);
  EXPECT_EQ(s.sin_q16[49152], -65536);
  std::printf("[slam] sine table: worst error %.3g (bound %.3g)\n", worst, 1.0 / 65536.0);
}

TEST(SlamSetup, SensorGeometryInIntegerUnitsMatchesTheDoubles) {
  const World world;
  for (const int beams : {36, 90, 361}) {
    Scan geometry = make_scan(world, {}, {}, 0.0, beams);
    geometry.angle0 = -2.1;  // not a whole number of units
    const SlamSetup s = make_slam_setup(small_config(), geometry, 0.5);
    ASSERT_EQ(s.sensor.bearing.size(), static_cast<std::size_t>(beams));
    for (int i = 0; i < beams; ++i)
      ASSERT_LE(std::abs(s.sensor.bearing[static_cast<std::size_t>(i)] * kUnit -
                         geometry.bearing(static_cast<std::size_t>(i))),
                0.5 * kUnit + 1e-12)
          << i;
    EXPECT_LE(std::abs(s.sensor.mount_x_mm - 1000.0 * kMount.x), 0.5);
    EXPECT_LE(std::abs(s.sensor.mount_y_mm - 1000.0 * kMount.y), 0.5);
    EXPECT_LE(std::abs(s.sensor.mount_theta * kUnit - kMount.theta), 0.5 * kUnit);
    EXPECT_EQ(s.cell_mm, 100);
    EXPECT_EQ(s.sigma_mm, 50);
    EXPECT_EQ(s.max_range_mm, 10000);
  }
}

TEST(SlamSetup, MapPutsTheSlamOriginCellOnTheOrigin) {
  const World world;
  for (const double cell : {0.1, 0.05, 0.037}) {
    GridSlamConfig c = small_config();
    c.cell = cell;
    const double reach = 3.3;
    const SlamSetup s = make_slam_setup(c, make_scan(world, {}, {}, 0.0, 90), reach);
    const GridGeometry& g = s.map_geometry;
    EXPECT_NEAR(g.centre_x(s.origin_cell_x), 0.0, 1e-9) << cell;
    EXPECT_NEAR(g.centre_y(s.origin_cell_y), 0.0, 1e-9) << cell;
    EXPECT_EQ(g.resolution, cell);
    EXPECT_EQ(g.cell_x(0.0), s.origin_cell_x);
    EXPECT_EQ(g.cell_y(0.0), s.origin_cell_y);
    // Every point within the odometry's reach plus a full-range reading, plus the margin, is in.
    const double needed = reach + c.sensor.max_range + c.map.margin;
    for (const double sx : {-1.0, 1.0})
      for (const double sy : {-1.0, 1.0})
        EXPECT_TRUE(g.contains(g.cell_x(sx * needed), g.cell_y(sy * needed))) << cell;
  }
}

TEST(SlamSetup, NarrowIsmTableIsTheScanInsertersBeams) {
  const World world;
  for (const int divisor : {1, 3}) {
    GridSlamConfig c = small_config();
    c.sensor.max_range = 6.0;
    c.map.empty_divisor = divisor;
    const SlamSetup s = make_slam_setup(c, make_scan(world, {}, {}, 0.0, 90), 0.0);
    const NarrowIsmTable& t = s.ism;
    EXPECT_EQ(t.z_step_mm, 12);  // cell / 8
    const std::size_t bins = static_cast<std::size_t>(s.max_range_mm / t.z_step_mm + 2);
    ASSERT_EQ(t.begin.size(), bins + 1);
    EXPECT_EQ(t.begin[0], t.begin[1]);  // a reading of 0 has no cells
    EXPECT_EQ(t.begin.back(), t.values.size());
    // The oracle: the integer scan inserter with the same model, codec and veto.
    IndexScanInserter<std::int8_t> inserter(GaussianBeamModel{c.sensor.sigma, 0.0}, c.cell, s.codec,
                                            VetoBound::strongest_claim, t.z_step_mm / 1000.0);
    std::size_t checked = 0;
    for (std::size_t b = 1; b < bins; b += 7) {
      const std::vector<std::int8_t>& beam =
          inserter.beam_indices(static_cast<double>(b) * t.z_step_mm / 1000.0);
      ASSERT_EQ(t.begin[b + 1] - t.begin[b], beam.size()) << b;
      bool positive = false;
      for (std::size_t k = 0; k < beam.size(); ++k) {
        const int n = beam[k];
        const int expected = n >= 0 ? n : -((-n + divisor - 1) / divisor);
        ASSERT_EQ(t.values[t.begin[b] + k], expected) << "bin " << b << " cell " << k;
        positive = positive || n > 0;
      }
      // Every reading claims some cell occupied, near z.
      EXPECT_TRUE(positive) << b;
      ++checked;
    }
    EXPECT_GT(checked, 50u);
    EXPECT_LE(std::abs(s.max_seps_index), 127);
    EXPECT_EQ(s.max_seps_index, s.codec.max_index());
  }
}

TEST(SlamSetup, ConfigCheckNamesEachBadField) {
  EXPECT_NO_THROW(check_grid_slam_config(GridSlamConfig{}));
  struct Case {
    const char* field;
    void (*spoil)(GridSlamConfig&);
  };
  const Case cases[] = {
      {"cell", [](GridSlamConfig& c) { c.cell = 0.1234; }},  // not a whole number of mm
      {"cell", [](GridSlamConfig& c) { c.cell = 0.0; }},
      {"headings", [](GridSlamConfig& c) { c.headings = 1000; }},
      {"headings", [](GridSlamConfig& c) { c.headings = 4; }},
      {"window.cells", [](GridSlamConfig& c) { c.window.cells = 10; }},
      {"window.headings", [](GridSlamConfig& c) { c.window.headings = 12; }},
      {"window.headings",
       [](GridSlamConfig& c) {
         c.headings = 8;
         c.window.headings = 9;
       }},
      {"schedule.lambda", [](GridSlamConfig& c) { c.schedule.lambda = 0; }},
      {"schedule.xi", [](GridSlamConfig& c) { c.schedule.xi = 0; }},
      {"sensor.sigma",
       [](GridSlamConfig& c) { c.sensor.sigma = std::numeric_limits<double>::quiet_NaN(); }},
      {"sensor.sigma", [](GridSlamConfig& c) { c.sensor.sigma = 0.0005; }},
      {"beam.likelihood_floor", [](GridSlamConfig& c) { c.beam.likelihood_floor = 0.0; }},
      {"beam.beams", [](GridSlamConfig& c) { c.beam.beams = 0; }},
      {"beam.tempering", [](GridSlamConfig& c) { c.beam.tempering = 0; }},
      {"sensor.max_range", [](GridSlamConfig& c) { c.sensor.max_range = -1.0; }},
      {"window.pose_cutoff", [](GridSlamConfig& c) { c.window.pose_cutoff = 0.0; }},
      {"window.pose_prune", [](GridSlamConfig& c) { c.window.pose_prune = -1e-9; }},
      {"window.pose_prune",
       [](GridSlamConfig& c) { c.window.pose_prune = std::numeric_limits<double>::quiet_NaN(); }},
      {"window.pose_prune", [](GridSlamConfig& c) { c.window.pose_prune = c.window.pose_cutoff; }},
      {"motion", [](GridSlamConfig& c) { c.motion.xy_per_m = -0.1; }},
      {"motion",
       [](GridSlamConfig& c) { c.motion.theta0 = std::numeric_limits<double>::infinity(); }},
      {"map.seps_bits", [](GridSlamConfig& c) { c.map.seps_bits = 9; }},
      // 128 > the largest index 127. (127 itself is accepted, though the message says "below
      // the largest index".)
      {"map.seps_levels", [](GridSlamConfig& c) { c.map.seps_levels = 128; }},
      {"map.empty_divisor", [](GridSlamConfig& c) { c.map.empty_divisor = 0; }},
      {"ugamma.bits", [](GridSlamConfig& c) { c.ugamma.bits = 32; }},
      {"ugamma.steps_per_halving", [](GridSlamConfig& c) { c.ugamma.steps_per_halving = 0; }},
      {"map.margin",
       [](GridSlamConfig& c) { c.map.margin = std::numeric_limits<double>::quiet_NaN(); }},
  };
  for (const Case& k : cases) {
    GridSlamConfig c;
    k.spoil(c);
    try {
      check_grid_slam_config(c);
      ADD_FAILURE() << "accepted a bad " << k.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(k.field), std::string::npos)
          << "message for " << k.field << ": " << e.what();
    }
    // make_slam_setup checks too.
    EXPECT_THROW(make_slam_setup(c, make_scan(World{}, {}, {}, 0.0, 36), 0.0),
                 std::invalid_argument)
        << k.field;
  }
  EXPECT_THROW(make_slam_setup(GridSlamConfig{}, make_scan(World{}, {}, {}, 0.0, 36), -1.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
