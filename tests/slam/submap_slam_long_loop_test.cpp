// A loop that comes back after many minutes: the simulated floor at 100 x 60 m, its corridor
// (about 300 m round) driven 400 m in 13 minutes, odometry that reports every turn 5% too large
// (28 m off at the end). A log of the benchmark's kind that the defaults never saw: the way
// round is longer than Intel's and ACES's loops, and the drift at the return reaches metres.
// Label long (Release only): about 10 s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "intgrid/simulation/simulator.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"
#include "simulated_run.hpp"

namespace intgrid::slam {
namespace {

double position_error(const SlamRun& run, const test::SimulatedRun& sim, std::size_t i) {
  return std::hypot(run.trajectory[i].pose.x - sim.truth[i].pose.x,
                    run.trajectory[i].pose.y - sim.truth[i].pose.y);
}

// The loop closes where the robot returns (its first lap's start, met again from scan 2400):
// measured 0.14 m off there at most, against the odometry's 28 m. The far side of the floor,
// driven once, keeps what the front end did there: up to 0.43 m off (scans 1200 to 2200; ATE
// 0.22 m). Most of it is the front end's translation coming out too long (0.18%): the exact ISM
// leans a fused wall outward by a part of its sigma (SubmapSlamConfig::Sensor::sigma; at the
// former 0.05 m: 0.34% too long, 0.60 m off on the far side, ATE 0.31 m, but 0.07 m at the
// return). The floors: 0.2 m at the return, 0.55 m on the far side, ATE 0.3 m, 0.6 m at worst.
TEST(SubmapSlamLongLoop, ClosesALoopThirteenMinutesRoundInInteger) {
  simulation::FloorplanConfig floor;
  floor.cell = 0.05;
  floor.width = 100;
  floor.height = 60;
  floor.furniture = 30;
  const simulation::Floorplan plan = simulation::make_floorplan(floor, 7);
  simulation::TrajectoryConfig route;
  route.scans = 4000;
  const std::vector<core::Pose2> truth = simulation::follow_route(plan.corridor_loop, true, route);
  const test::SimulatedRun sim = test::record_run(
      plan.grid, truth, 9, simulation::lidar_sensor(361, std::numbers::pi, 20.0), 13, 1.05);
  SubmapSlamStats stats;
  const SlamRun run =
      run_submap_slam(sim.log, SubmapSlamConfig{}, core::Arithmetic::integer, &stats);
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  const double odometry_end = std::hypot(sim.log.scans.back().robot.x - truth.back().x,
                                         sim.log.scans.back().robot.y - truth.back().y);
  double far_side = 0.0, back_at_the_start = 0.0;
  for (std::size_t i = 1200; i <= 2200; ++i)
    far_side = std::max(far_side, position_error(run, sim, i));
  for (std::size_t i = 2800; i <= 3000; ++i)
    back_at_the_start = std::max(back_at_the_start, position_error(run, sim, i));
  std::printf(
      "long loop: ATE %.3f m (max %.3f m), the far side %.3f m off at most, back at the start "
      "%.3f m; odometry %.1f m off at the end; %zu closures of %zu searches\n",
      slam.rmse, slam.max, far_side, back_at_the_start, odometry_end, stats.loop_closures,
      stats.loop_searches);
  EXPECT_GT(odometry_end, 10.0);  // the drift at the return is metres: the test means something
  EXPECT_LT(back_at_the_start, 0.2);
  EXPECT_LT(far_side, 0.55);
  EXPECT_LT(slam.rmse, 0.3);
  EXPECT_LT(slam.max, 0.6);
}

}  // namespace
}  // namespace intgrid::slam
