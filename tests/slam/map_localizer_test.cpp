// MapLocalizer: the SLAM's localization event against a map given whole. The oracle is the
// simulator's truth: the map is the simulated world itself, in S_eps indices, so the scans fit
// it at the true poses and nowhere else; the odometry drifts about a metre in one lap.
#include "intgrid/slam/map_localizer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/simulation/simulator.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "simulated_run.hpp"

namespace intgrid::slam {
namespace {

using test::record_run;
using test::SimulatedRun;

struct World {
  core::ProbabilityGrid grid;
  SimulatedRun run;
};

// The corridor loop of the simulated floor (5 cm cells), 500 scans at 361 beams.
const World& loop_world() {
  static const World world = [] {
    simulation::FloorplanConfig floor;
    floor.cell = 0.05;
    const simulation::Floorplan plan = simulation::make_floorplan(floor, 5);
    simulation::TrajectoryConfig route;
    route.scans = 500;
    const std::vector<core::Pose2> truth =
        simulation::follow_route(plan.corridor_loop, true, route);
    return World{plan.grid, record_run(plan.grid, truth, 9,
                                       simulation::lidar_sensor(361, std::numbers::pi, 20.0), 13)};
  }();
  return world;
}

// The world as a SLAM would map it, in the SLAM's codec: the surface of each obstacle (its cells
// next to free space) at the largest index, free cells at its negative, the obstacles' insides
// unknown (0), as no ray reaches them.
core::Grid<std::int8_t> world_map(const core::ProbabilityGrid& world, const SubmapSlamConfig& c) {
  const core::GridGeometry& g = world.geometry;
  const auto free = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < g.width && y < g.height && world.at(x, y) < 0.5;
  };
  core::ProbabilityGrid seen(g, std::numeric_limits<double>::quiet_NaN());
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const bool surface = free(x - 1, y) || free(x + 1, y) || free(x, y - 1) || free(x, y + 1);
      if (free(x, y))
        seen.at(x, y) = 0.0;
      else if (surface)
        seen.at(x, y) = 1.0;
    }
  return map_indices(seen, c);  // 0 and 1 saturate to the largest indices, NaN is 0
}

struct TrackingError {
  double worst_m = 0.0, worst_degrees = 0.0;
  std::size_t matched = 0;
};

TrackingError track(const core::Pose2& initial, std::size_t skip, core::Arithmetic arithmetic) {
  const World& w = loop_world();
  const SubmapSlamConfig config;
  MapLocalizer localizer(config, arithmetic, world_map(w.grid, config), initial);
  TrackingError e;
  for (std::size_t i = 0; i < w.run.log.scans.size(); ++i) {
    const MapFix fix = localizer.localize(w.run.log.scans[i]);
    e.matched += fix.matched;
    if (i < skip) continue;
    const core::Pose2& truth = w.run.truth[i].pose;
    e.worst_m = std::max(e.worst_m, std::hypot(fix.pose.x - truth.x, fix.pose.y - truth.y));
    e.worst_degrees =
        std::max(e.worst_degrees,
                 std::abs(std::remainder(fix.pose.theta - truth.theta, 2 * std::numbers::pi)) *
                     180 / std::numbers::pi);
  }
  return e;
}

double odometry_worst_m() {
  const World& w = loop_world();
  double worst = 0.0;
  const core::Pose2 start = w.run.truth.front().pose;
  const core::Pose2 odometry0 = w.run.log.scans.front().robot;
  for (std::size_t i = 0; i < w.run.log.scans.size(); ++i) {
    // The odometry carried from the true start, as a tracker without a map would have it.
    const core::Pose2 p = core::compose(start, core::relative(odometry0, w.run.log.scans[i].robot));
    worst = std::max(worst, std::hypot(p.x - w.run.truth[i].pose.x, p.y - w.run.truth[i].pose.y));
  }
  return worst;
}

void tracks_the_loop(core::Arithmetic arithmetic) {
  const TrackingError e = track(loop_world().run.truth.front().pose, 0, arithmetic);
  const double odometry = odometry_worst_m();
  std::printf("tracked in the world's map: at most %.3f m and %.2f degrees off, odometry %.3f m\n",
              e.worst_m, e.worst_degrees, odometry);
  // Measured 0.056 m and 1.33 degrees (integer and double) against the odometry's 2.08 m.
  EXPECT_GT(odometry, 0.5);  // the odometry alone drifts: the test means something
  EXPECT_EQ(e.matched, loop_world().run.log.scans.size());
  EXPECT_LT(e.worst_m, 0.1);
  EXPECT_LT(e.worst_degrees, 2.0);
}

TEST(MapLocalizer, TracksTheLoopInTheWorldsMapInInteger) {
  tracks_the_loop(core::Arithmetic::integer);
}
TEST(MapLocalizer, TracksTheLoopInTheWorldsMapInDouble) {
  tracks_the_loop(core::Arithmetic::floating);
}

// Started 0.18 m and 5 degrees off the true pose, inside the narrow window: found within 10
// scans (measured: at most 0.052 m and 1.25 degrees off from the tenth on).
TEST(MapLocalizer, FindsThePoseFromAStartWithinTheWindow) {
  core::Pose2 start = loop_world().run.truth.front().pose;
  start.x += 0.15;
  start.y -= 0.1;
  start.theta += 5 * std::numbers::pi / 180;
  const TrackingError e = track(start, 10, core::Arithmetic::integer);
  std::printf("started off: at most %.3f m and %.2f degrees off from the 10th scan on\n", e.worst_m,
              e.worst_degrees);
  EXPECT_LT(e.worst_m, 0.1);
  EXPECT_LT(e.worst_degrees, 2.0);
}

TEST(MapLocalizer, RefusesAMapOfAnotherCellOrIndexRange) {
  const World& w = loop_world();
  SubmapSlamConfig config;
  const core::Grid<std::int8_t> map = world_map(w.grid, config);
  config.cell = 0.1;
  try {
    MapLocalizer(config, core::Arithmetic::integer, map, {});
    FAIL() << "a map of 5 cm cells taken at 10 cm";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cell"), std::string::npos) << e.what();
  }
  config = SubmapSlamConfig{};
  config.map.seps_bits = 6;  // largest index 31: the map's 127 lies beyond it
  try {
    MapLocalizer(config, core::Arithmetic::integer, map, {});
    FAIL() << "indices beyond the codec's";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("map"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace intgrid::slam
