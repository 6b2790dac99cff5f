// The bundled real log through the SLAM end to end, scored against the reference trajectory
// (data/README.md). The target is ATE <= 0.20 m; what the default settings reach is in
// the README, and these floors sit a little above it so that a regression fails.
#include <gtest/gtest.h>

#include <cmath>

#include "golden/slam_run.hpp"
#include "golden/trajectory_metrics.hpp"
#include "host/log_io.hpp"

namespace intgrid {
namespace {

const std::string kData = INTGRID_DATA_DIR;

struct Scored {
  SlamRun run;
  TrajectoryError ate;
};

Scored run_and_score(Arithmetic arithmetic) {
  const Log log = read_log(kData + "/malaga_telecom_loop.log");
  const Log reference = read_log(kData + "/malaga_telecom_loop_reference.log");
  Scored s{run_slam(log, SlamConfig{}, arithmetic), {}};
  s.ate = absolute_trajectory_error(s.run.trajectory, scan_poses(reference));
  return s;
}

TEST(SlamData, RealLogTrajectoryErrorFloorAndArithmeticsAgree) {
  const Scored integer = run_and_score(Arithmetic::integer);
  const Scored floating = run_and_score(Arithmetic::floating);
  EXPECT_EQ(integer.run.scans, 225u);
  EXPECT_EQ(integer.ate.matched, 99u);
  EXPECT_EQ(integer.run.localizations, 224u);
  EXPECT_EQ(integer.run.mappings, 225u);
  // Measured 0.236 m (integer) and 0.298 m (double); raw odometry is 3.66 m. The run is
  // sensitive to small changes in either arithmetic (README), so the arithmetics are held to
  // one side only: U_gamma must not cost accuracy against double.
  EXPECT_LT(integer.ate.rmse, 0.30);
  EXPECT_LT(floating.ate.rmse, 0.40);
  EXPECT_LT(integer.ate.rmse, 1.1 * floating.ate.rmse);
  // The map: the courtyard's walls are there, and most of what the laser crossed is empty.
  std::size_t occupied = 0, empty = 0;
  for (const std::int8_t n : integer.run.map.cells) {
    occupied += n > 0;
    empty += n < 0;
  }
  EXPECT_GT(occupied, 2000u);
  EXPECT_GT(empty, 20 * occupied);
}

TEST(SlamData, OdometryAloneIsFarFromTheReference) {
  const Log log = read_log(kData + "/malaga_telecom_loop.log");
  const Log reference = read_log(kData + "/malaga_telecom_loop_reference.log");
  const TrajectoryError odometry =
      absolute_trajectory_error(scan_poses(log), scan_poses(reference));
  EXPECT_GT(odometry.rmse, 3.0);
}

}  // namespace
}  // namespace intgrid
