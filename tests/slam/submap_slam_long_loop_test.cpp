// A loop that comes back after many minutes: the simulated floor at 100 x 60 m, its corridor
// (about 300 m round) driven 400 m in 13 minutes, odometry that reports every turn 5% too large
// (28 m off at the end). A log of the benchmark's kind that the defaults never saw: the way
// round is longer than Intel's and ACES's loops, and the drift at the return reaches metres.
// Label long (Release only): about 25 s (the run with young nodes matched again and without).
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
// measured 0.034 m off there at most, against the odometry's 28 m. The far side of the floor,
// driven once, keeps what the front end did there: up to 0.26 m off (scans 1200 to 2200; ATE
// 0.150 m, 0.262 m at worst). Part of it is the front end's translation coming out too long
// (0.18%): the exact ISM leans a fused wall outward by a part of its sigma
// (SubmapSlamConfig::Sensor::sigma). Without young nodes matched again
// (SubmapSlamConfig::Submaps::rematch) 0.14 m at the return, 0.43 m on the far side, ATE 0.22 m,
// 0.45 m at worst; the test runs both. The floors: 0.1 m at the return, 0.35 m on the far side,
// ATE 0.2 m, 0.4 m at worst, and each figure no worse than without.
struct LongLoopErrors {
  double rmse = 0.0, max = 0.0, far_side = 0.0, back_at_the_start = 0.0;
};

LongLoopErrors run_long_loop(const test::SimulatedRun& sim, bool rematch) {
  SubmapSlamConfig config;
  config.submaps.rematch = rematch;
  SubmapSlamStats stats;
  const SlamRun run = run_submap_slam(sim.log, config, core::Arithmetic::integer, &stats);
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  LongLoopErrors e{slam.rmse, slam.max};
  for (std::size_t i = 1200; i <= 2200; ++i)
    e.far_side = std::max(e.far_side, position_error(run, sim, i));
  for (std::size_t i = 2800; i <= 3000; ++i)
    e.back_at_the_start = std::max(e.back_at_the_start, position_error(run, sim, i));
  std::printf(
      "long loop, young nodes %s: ATE %.3f m (max %.3f m), the far side %.3f m off at most, back "
      "at the start %.3f m; %zu closures of %zu searches\n",
      rematch ? "matched again" : "as placed", e.rmse, e.max, e.far_side, e.back_at_the_start,
      stats.loop_closures, stats.loop_searches);
  return e;
}

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
  const double odometry_end = std::hypot(sim.log.scans.back().robot.x - truth.back().x,
                                         sim.log.scans.back().robot.y - truth.back().y);
  std::printf("long loop: odometry %.1f m off at the end\n", odometry_end);
  EXPECT_GT(odometry_end, 10.0);  // the drift at the return is metres: the test means something
  const LongLoopErrors with = run_long_loop(sim, true);
  const LongLoopErrors without = run_long_loop(sim, false);
  EXPECT_LT(with.back_at_the_start, 0.1);
  EXPECT_LT(with.far_side, 0.35);
  EXPECT_LT(with.rmse, 0.2);
  EXPECT_LT(with.max, 0.4);
  EXPECT_LE(with.back_at_the_start, without.back_at_the_start);
  EXPECT_LE(with.far_side, without.far_side);
  EXPECT_LE(with.rmse, without.rmse);
}

}  // namespace
}  // namespace intgrid::slam
