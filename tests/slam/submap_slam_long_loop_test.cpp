// A loop that comes back after many minutes: the simulated floor at 100 x 60 m, its corridor
// (about 300 m round) driven 400 m in 13 minutes, odometry that reports every turn 5% too large
// (28 m off at the end). A log of the benchmark's kind that the defaults never saw: the way
// round is longer than Intel's and ACES's loops, and the drift at the return reaches metres.
// And a loop whose front end itself drifts metres, along a blind corridor. Label long (Release
// only): about 30 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

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
// measured 0.027 m off there at most, against the odometry's 28 m. The far side of the floor,
// driven once, keeps what the front end did there: up to 0.27 m off (scans 1200 to 2200; ATE
// 0.142 m, 0.279 m at worst). Part of it is the front end's translation coming out too long
// (0.18%): the exact ISM leans a fused wall outward by a part of its sigma
// (SubmapSlamConfig::sensor.sigma). The floors: 0.1 m at the return, 0.35 m on the far side,
// ATE 0.2 m, 0.4 m at worst.

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
  SubmapSlamStats stats;
  const SlamRun run =
      run_submap_slam(sim.log, SubmapSlamConfig{}, core::Arithmetic::integer, &stats);
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  double far_side = 0, back_at_the_start = 0;
  for (std::size_t i = 1200; i <= 2200; ++i)
    far_side = std::max(far_side, position_error(run, sim, i));
  for (std::size_t i = 2800; i <= 3000; ++i)
    back_at_the_start = std::max(back_at_the_start, position_error(run, sim, i));
  std::printf(
      "long loop: ATE %.3f m (max %.3f m), the far side %.3f m off at most, back at the start "
      "%.3f m; %zu closures of %zu searches\n",
      slam.rmse, slam.max, far_side, back_at_the_start, stats.loop_closures, stats.loop_searches);
  EXPECT_LT(back_at_the_start, 0.1);
  EXPECT_LT(far_side, 0.35);
  EXPECT_LT(slam.rmse, 0.2);
  EXPECT_LT(slam.max, 0.4);
}

// A loop whose front end drifts metres before it comes back: a blind corridor 92 m long and 2 m
// wide with plain walls (a hospital's or a basement's) joins two rooms with pillars, and a second
// corridor with doorways at uneven spacing leads back. The odometry reports every move 8% too
// long (a wheel radius calibrated wrong); with 8 m of range the scans fix nothing along the blind
// corridor for about 84 m, so the front end follows the odometry there and comes out about 6.7 m
// too far, and the way back, well seen, carries that offset into the first room. The closure that
// ties the return to the first room's submaps is found metres from the graph's estimate (within
// the drift check's reach, SubmapSlamConfig::LoopClosure::drift), and the graph must then
// shorten the blind corridor, which only the odometry measured.
test::SimulatedRun blind_corridor_loop() {
  core::ProbabilityGrid world(core::GridGeometry{2200, 440, 0.05, 0.0, 0.0}, 1.0);
  const auto carve = [&](double x0, double y0, double x1, double y1, double value) {
    test::fill_rectangle(world, x0, y0, x1, y1, value);
  };
  carve(1, 1, 9, 21, 0.0);      // the west room
  carve(101, 1, 109, 21, 0.0);  // the east room
  carve(9, 4, 101, 6, 0.0);     // the blind corridor
  carve(9, 15, 101, 17, 0.0);   // the way back
  // The way back's doorways, north and south, at uneven spacing: each stretch looks like itself.
  double x = 10.0;
  for (int k = 0; x < 99.0; ++k) {
    const double width = 0.8 + 0.1 * static_cast<double>(k % 5);
    if (k % 2 == 0)
      carve(x, 17, x + width, 17.8, 0.0);
    else
      carve(x, 14.2, x + width, 15, 0.0);
    x += 2.1 + 0.7 * static_cast<double>((k * 7) % 5);
  }
  for (const auto& [px, py] : std::vector<std::pair<double, double>>{{2.5, 9},
                                                                     {7.5, 11},
                                                                     {2.5, 13.5},
                                                                     {7.5, 19},
                                                                     {3, 2.5},
                                                                     {103, 9},
                                                                     {107, 12},
                                                                     {103.5, 13.5},
                                                                     {106, 2.5},
                                                                     {104, 19}})
    carve(px, py, px + 0.5, py + 0.5, 1.0);  // the rooms' pillars
  simulation::TrajectoryConfig route;
  route.scans = 2460;  // a lap (about 2260 scans) and 20 m into the blind corridor again
  const std::vector<core::Pose2> truth =
      simulation::follow_route({{5, 5}, {105, 5}, {105, 16}, {5, 16}}, true, route);
  return test::record_run(world, truth, 51, simulation::lidar_sensor(361, std::numbers::pi, 8.0),
                          53, 1.0, 1.08);
}

// The return: the scans of the second visit to the west room, after the way back. The closure
// to the first room's submaps takes the nodes of the blind corridor with it, since their edges to
// their submaps hold nothing along it (SubmapSlamConfig::Graph::local_sigma_xy): measured 0.20 m
// off there at most (integer; double 0.20 m), ATE 1.49 m (1.57 m), against 4.34 m and 4.93 m
// with those edges at full weight in every direction, where the graph held the corridor's length
// against the closure (found 4.2 m from the estimate) and switched it off. What is left is not
// the graph's: the loop measures only the difference of the two corridors' lengths, and the
// front end carried part of the odometry's error along the way back too (its doorways fix
// little along it, and its matches lean toward the prediction): 102.45 m for the true 100 m,
// against 106.9 m along the blind corridor, so the return came 4.45 m off and the graph, giving
// nearly all of it to the blind corridor, left that 2.5 m too long and the way back 2.35 m too
// long. The floors: 0.5 m in the west room, ATE 2 m.
void closes_a_loop_after_a_blind_corridor(core::Arithmetic arithmetic) {
  const test::SimulatedRun sim = blind_corridor_loop();
  std::size_t first = 0;
  while (first < sim.truth.size() && !(sim.truth[first].pose.y > 10 && sim.truth[first].pose.x < 9))
    ++first;
  ASSERT_LT(first, sim.truth.size());
  std::size_t last = first;
  while (last + 1 < sim.truth.size() && sim.truth[last + 1].pose.x < 9) ++last;
  std::size_t east = 0;  // where the blind corridor ends
  while (sim.truth[east].pose.x < 101) ++east;
  const double odometry_east = sim.log.scans[east].robot.x - sim.truth[east].pose.x;
  EXPECT_GT(odometry_east, 5.0);  // the drift is more than the former search window reached
  SubmapSlamStats stats;
  const SlamRun slam = run_submap_slam(sim.log, SubmapSlamConfig{}, arithmetic, &stats);
  double back = 0;
  for (std::size_t i = first; i <= last; ++i) back = std::max(back, position_error(slam, sim, i));
  const TrajectoryError e = absolute_trajectory_error(slam.trajectory, sim.truth);
  std::printf(
      "blind corridor loop: odometry %.2f m too far where the corridor ends; back in the west room "
      "(scans %zu to %zu) %.3f m off at most; ATE %.3f m (max %.3f m); %zu closures of %zu "
      "searches, %zu switched off\n",
      odometry_east, first, last, back, e.rmse, e.max, stats.loop_closures, stats.loop_searches,
      stats.switched_off_closures);
  EXPECT_LT(back, 0.5);
  EXPECT_LT(e.rmse, 2.0);
}

TEST(SubmapSlamLongLoop, ClosesALoopAfterABlindCorridorInInteger) {
  closes_a_loop_after_a_blind_corridor(core::Arithmetic::integer);
}
TEST(SubmapSlamLongLoop, ClosesALoopAfterABlindCorridorInDouble) {
  closes_a_loop_after_a_blind_corridor(core::Arithmetic::floating);
}

}  // namespace
}  // namespace intgrid::slam
