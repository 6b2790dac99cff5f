// Logs as the SLAM takes them, the schedule, the trajectory error by hand, and GridSlam as the
// per-scan path.
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
// 7. Logs: checks, quantization, the schedule.

Log small_log(int scans, int beams = 36) {
  Log log;
  for (int i = 0; i < scans; ++i) {
    const Pose2 pose{0.05 * i, 0.0, 0.01 * i};
    log.scans.push_back(make_scan(World{}, pose, pose, 10.0 + 0.1 * i, beams));
  }
  return log;
}

std::string log_error(const Log& log) {
  try {
    check_slam_log(log);
    check_one_sensor_geometry(log);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SlamLog, CheckRejectsWhatSlamCannotUse) {
  EXPECT_NE(log_error(Log{}), "");
  EXPECT_EQ(log_error(small_log(1)), "");  // one scan, no motion needed
  EXPECT_EQ(log_error(small_log(5)), "");

  Log still = small_log(4);
  for (Scan& s : still.scans) s.robot = still.scans[0].robot;
  EXPECT_NE(log_error(still).find("odometry"), std::string::npos) << log_error(still);
  still.odometry.push_back({10.0, {}});  // an ODOM record makes it usable
  EXPECT_EQ(log_error(still), "");

  Log beams = small_log(5);
  beams.scans[2].ranges.pop_back();
  const std::string m = log_error(beams);
  EXPECT_NE(m.find("scan 3"), std::string::npos) << m;
  EXPECT_NE(m.find("beam count"), std::string::npos) << m;

  Log mount = small_log(5);
  mount.scans[3].sensor_mount.x += 0.01;
  EXPECT_NE(log_error(mount).find("scan 4"), std::string::npos) << log_error(mount);

  Log bearing = small_log(5);
  bearing.scans[1].dangle *= 1.001;
  EXPECT_NE(log_error(bearing).find("scan 2"), std::string::npos) << log_error(bearing);

  EXPECT_THROW(run_grid_slam(beams, small_config(), Arithmetic::integer), std::invalid_argument);
}

TEST(SlamLog, QuantizationCountsAndZeroesUnusableReadings) {
  Log log = small_log(3, 10);
  GridSlamConfig config = small_config();
  config.sensor.max_range = 5.0;
  std::vector<double>& r = log.scans[1].ranges;
  r = {0.0,    std::numeric_limits<double>::quiet_NaN(),
       -1.0,   std::numeric_limits<double>::infinity(),
       5.0,   // at the configured max range
       25.0,  // past the sensor's
       1.2344, 4.9994,
       0.0004, 2.0};
  SlamRun counts;
  const std::vector<QuantizedScan> q = quantize_scans(log, config, counts);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(counts.readings, 30u);
  // Scan 1: seven unusable (0, NaN, -1, inf, 5.0, 25, 0.0004 rounding to 0 mm).
  EXPECT_EQ(counts.unusable_readings, 7u);
  EXPECT_EQ(q[1].range_mm, (std::vector<std::int32_t>{0, 0, 0, 0, 0, 0, 1234, 4999, 0, 2000}));
  // Odometry increments: the relative pose of consecutive scans, in mm and angle units.
  EXPECT_EQ(q[0].odom_dx_mm, 0);
  const Pose2 u = relative(log.scans[0].robot, log.scans[1].robot);
  EXPECT_EQ(q[1].odom_dx_mm, std::lround(u.x * 1000.0));
  EXPECT_EQ(q[1].odom_dy_mm, std::lround(u.y * 1000.0));
  EXPECT_EQ(q[1].odom_dtheta, std::lround(u.theta / kUnit));
  EXPECT_EQ(q[1].odom_dtheta, 104);  // 0.01 rad
}

TEST(SlamLog, ScheduleAndScansWithoutReadings) {
  // 360 beams: see SlamLocalization on sparse scans. Steps of half a cell, exact odometry.
  Log log = small_log(10, 360);
  for (double& r : log.scans[4].ranges) r = std::numeric_limits<double>::quiet_NaN();
  GridSlamConfig config = small_config();
  config.schedule.lambda = 2;
  config.schedule.xi = 3;
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const SlamRun run = run_grid_slam(log, config, a);
    EXPECT_EQ(run.scans, 10u);
    EXPECT_EQ(run.trajectory.size(), 10u);
    EXPECT_EQ(run.skipped_scans, 1u);
    EXPECT_EQ(run.unusable_readings, 360u);
    // Mapping at scans 0, 3, 6, 9; localization at the even scans after the first mapping,
    // but not at the skipped scan 4: 2, 6, 8.
    EXPECT_EQ(run.mappings, 4u);
    EXPECT_EQ(run.localizations, 3u);
    // The run continued, and tracked: the last estimate is within half a cell of the last
    // (exact) odometry pose (measured: 0.45 m of 0.45 m in both arithmetics).
    const Pose2& last = run.trajectory.back().pose;
    EXPECT_NEAR(last.x, log.scans.back().robot.x, 0.05);
    EXPECT_NEAR(last.y, log.scans.back().robot.y, 0.05);
    EXPECT_EQ(run.trajectory[4].t, log.scans[4].t);
  }
}

// ---------------------------------------------------------------------------------------------
// 8. Absolute trajectory error.

TEST(TrajectoryError, HandComputedExample) {
  const std::vector<TimedPose> estimate = {
      {1.0000, {0.0, 0.0, 0.1}},
      {2.0004, {3.0, 4.0, 3.0}},  // matches 2.0 within 1 ms
      {2.9980, {9.0, 9.0, 0.0}},  // 2 ms before 3.0: no match
  };
  const std::vector<TimedPose> reference = {
      {1.0, {0.0, 1.0, 0.0}},
      {2.0, {0.0, 0.0, -3.0}},
      {3.0, {0.0, 0.0, 0.0}},
  };
  const TrajectoryError e = absolute_trajectory_error(estimate, reference);
  EXPECT_EQ(e.matched, 2u);
  // Errors 1 and 5: rmse sqrt((1 + 25) / 2) = sqrt(13), max 5.
  EXPECT_NEAR(e.rmse, std::sqrt(13.0), 1e-12);
  EXPECT_DOUBLE_EQ(e.max, 5.0);
  // Headings: 0.1, and 3 - (-3) = 6 wraps to 2 pi - 6.
  EXPECT_NEAR(e.mean_heading, (0.1 + (2.0 * kPi - 6.0)) / 2.0, 1e-12);

  const std::vector<TimedPose> late = {{5.0, {}}};
  EXPECT_THROW(absolute_trajectory_error(late, reference), std::invalid_argument);
  EXPECT_THROW(absolute_trajectory_error(estimate, std::span<const TimedPose>{}),
               std::invalid_argument);
}

TEST(TrajectoryError, ScanPosesAreTheLogsRobotPoses) {
  const Log log = small_log(3);
  const std::vector<TimedPose> p = scan_poses(log);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2].t, log.scans[2].t);
  EXPECT_EQ(p[2].pose.x, log.scans[2].robot.x);
  const TrajectoryError e = absolute_trajectory_error(p, p);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.matched, 3u);
}

// GridSlam, scan by scan in SI units, against the per-scan path driven by hand: GridSlamEngine over
// quantize_scans' integer inputs, its estimate composed with the first pose.
template <class Pr>
void expect_grid_slam_is_the_per_scan_path(Arithmetic arithmetic) {
  const Log& log = loop_log().log;
  const GridSlamConfig config = loop_config();
  const Pose2 first = log.scans.front().robot;
  const double reach = odometry_reach(log.scans);
  const SlamSetup setup = make_slam_setup(config, log.scans.front(), reach);
  GridSlamEngine<Pr> by_hand(setup, make_probabilities<Pr>(setup));
  GridSlam online(config, arithmetic, log.scans.front(), reach);
  const std::vector<QuantizedScan> scans = quantize(log, config);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    by_hand.process(scans[i]);
    online.insert(log.scans[i]);
    const Pose2 expected = compose(first, pose_of(by_hand.estimate()));
    const Pose2 got = online.pose();
    ASSERT_EQ(got.x, expected.x) << "scan " << i;
    ASSERT_EQ(got.y, expected.y) << "scan " << i;
    ASSERT_EQ(got.theta, wrap_angle(expected.theta)) << "scan " << i;
    ASSERT_EQ(online.sigma(), static_cast<double>(by_hand.estimate().sigma_um) * 1e-6);
  }
  EXPECT_EQ(online.map().cells, by_hand.map().cells);
  EXPECT_EQ(online.scans(), log.scans.size());
  EXPECT_EQ(online.localizations(), by_hand.localizations());
  EXPECT_EQ(online.mappings(), by_hand.mappings());
  // The whole-log run is the same scans through GridSlam.
  const SlamRun& run = loop_run(arithmetic);
  EXPECT_EQ(run.trajectory.back().pose.x, online.pose().x);
  EXPECT_EQ(run.map.cells, online.map().cells);
}

TEST(GridSlam, IsThePerScanPathInInteger) {
  expect_grid_slam_is_the_per_scan_path<IndexProbabilities>(Arithmetic::integer);
}

TEST(GridSlam, IsThePerScanPathInDouble) {
  expect_grid_slam_is_the_per_scan_path<DoubleProbabilities>(Arithmetic::floating);
}

TEST(GridSlam, RefusesAScanOfAnotherGeometryNamingIt) {
  const Log& log = loop_log().log;
  GridSlam slam(loop_config(), Arithmetic::integer, log.scans.front(), 5.0);
  slam.insert(log.scans[0]);
  Scan other = log.scans[1];
  other.sensor_mount.x += 0.01;
  try {
    slam.insert(other);
    FAIL() << "accepted another sensor mount";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scan 2 (t = 1000.200000) has another sensor mount"),
              std::string::npos)
        << e.what();
  }
  Scan far = log.scans[1];
  far.robot.x += 2000.0;
  EXPECT_THROW(slam.insert(far), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
