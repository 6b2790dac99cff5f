// The grid SLAM on the whole bundled real log, and on the courtyard simulated along its reference
// trajectory: the Release pass only (label long); slam_data_test.cpp's segment runs the same code
// under the sanitizers. The target is ATE <= 0.20 m; what the default settings reach is
// in docs/results.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "intgrid/io/map_io.hpp"
#include "intgrid/simulation/simulator.hpp"
#include "real_log_run.hpp"

namespace intgrid::slam::test {
namespace {

using core::Arithmetic;
using core::Log;
using core::Scan;

TEST(SlamData, RealLogTrajectoryErrorFloorAndArithmeticsAgree) {
  const Scored integer = run_real_log(Arithmetic::integer);
  const Scored floating = run_real_log(Arithmetic::floating);
  EXPECT_EQ(integer.run.scans, 225u);
  EXPECT_EQ(integer.ate.matched, 99u);
  EXPECT_EQ(integer.run.localizations, 224u);
  EXPECT_EQ(integer.run.mappings, 225u);
  // Measured 0.188 m (integer) and 0.191 m (double); raw odometry is 3.66 m. The issue's
  // target, and the two arithmetics within 10% of each other.
  EXPECT_LE(integer.ate.rmse, 0.20);
  EXPECT_LE(floating.ate.rmse, 0.20);
  EXPECT_LE(std::abs(integer.ate.rmse - floating.ate.rmse),
            0.1 * std::max(integer.ate.rmse, floating.ate.rmse));
  // The default tempering's reason (GridSlamConfig::tempering): the pose grid's spread is no
  // smaller than the rounding of its 10 cm lattice, cell sqrt(2/12) (measured 43.0 and 42.6 mm).
  const double lattice_rounding = GridSlamConfig{}.cell * std::sqrt(2.0 / 12.0);
  EXPECT_GE(integer.run.mean_sigma(), lattice_rounding);
  EXPECT_GE(floating.run.mean_sigma(), lattice_rounding);
  // The map: the courtyard's walls are there, and most of what the laser crossed is empty.
  std::size_t occupied = 0, empty = 0;
  for (const std::int8_t n : integer.run.map.cells) {
    occupied += n > 0;
    empty += n < 0;
  }
  EXPECT_GT(occupied, 2000u);
  EXPECT_GT(empty, 20 * occupied);
}

// The courtyard simulated along the reference trajectory (99 scans some 0.6 s apart, a metre and
// up to 10 degrees a step), with the simulator's default odometry noise: its heading misses by
// 2.9 degrees a step (standard deviation), past the motion model's 3 sigma at times. The pose
// grid's heading window must hold the true heading anyway, or the map turns with the error.
// Measured 0.126, 0.265 and 0.122 m (seeds 1 to 3); with the former +-3.5 degree window (21
// headings) and tempering 3, 0.850, 0.390 and 0.264 m. Integer only: the real-log test compares the
// arithmetics.
TEST(SlamData, SimulatedCourtyardKeepsTheTrueHeadingWhenOdometryMissesByDegrees) {
  const std::string data = intgrid::test::data_dir();
  const io::RosMap world = io::read_ros_map(data + "/malaga_telecom_map.yaml");
  const Log reference = io::read_log(data + "/malaga_telecom_loop_reference.log");
  simulation::SimulationConfig sim;
  for (const Scan& scan : reference.scans) sim.true_poses.push_back(scan.robot);
  sim.sensor = simulation::lidar_sensor(361, std::numbers::pi, 30.0);
  sim.sensor.occupied_threshold = world.occupied_thresh;
  double total = 0.0;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const simulation::Simulation run = simulation::simulate(world.grid, sim, seed);
    const std::vector<TimedPose> truth = scan_poses(run.truth);
    EXPECT_GT(absolute_trajectory_error(scan_poses(run.log), truth).rmse, 1.0) << "seed " << seed;
    const double ate =
        absolute_trajectory_error(
            run_grid_slam(run.log, GridSlamConfig{}, Arithmetic::integer).trajectory, truth)
            .rmse;
    EXPECT_LT(ate, 0.35) << "seed " << seed;
    total += ate;
  }
  EXPECT_LT(total / 3.0, 0.2);
}

}  // namespace
}  // namespace intgrid::slam::test
