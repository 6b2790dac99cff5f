// The grid SLAM on the bundled real log, a short segment of it: it runs in both passes, the
// sanitized one included (the whole log's runs are slam_log_long_test.cpp's, label long).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "real_log_run.hpp"

namespace intgrid::slam::test {
namespace {

using core::Arithmetic;

// The first 80 of the log's 225 scans: the robot has crossed the courtyard's first side, 23 of
// them have a reference pose, and the odometry has drifted 0.87 m (ATE) by then. Measured 0.189 m
// (integer) and 0.188 m (double): the whole log's floor (0.20 m) already holds here.
TEST(SlamData, RealLogSegmentBeatsTheOdometryInBothArithmetics) {
  const Scored integer = run_real_log(Arithmetic::integer, 80);
  const Scored floating = run_real_log(Arithmetic::floating, 80);
  for (const Scored* s : {&integer, &floating}) {
    EXPECT_EQ(s->run.scans, 80u);
    EXPECT_EQ(s->run.localizations, 79u);
    EXPECT_EQ(s->run.mappings, 80u);
    EXPECT_EQ(s->ate.matched, 23u);
    EXPECT_GT(s->odometry.rmse, 0.5);
    EXPECT_LE(s->ate.rmse, 0.20);
  }
  EXPECT_LE(std::abs(integer.ate.rmse - floating.ate.rmse),
            0.1 * std::max(integer.ate.rmse, floating.ate.rmse));
}

TEST(SlamData, OdometryAloneIsFarFromTheReference) {
  const std::string data = intgrid::test::data_dir();
  const TrajectoryError odometry = absolute_trajectory_error(
      scan_poses(io::read_log(data + "/malaga_telecom_loop.log")),
      scan_poses(io::read_log(data + "/malaga_telecom_loop_reference.log")));
  EXPECT_GT(odometry.rmse, 3.0);
}

}  // namespace
}  // namespace intgrid::slam::test
