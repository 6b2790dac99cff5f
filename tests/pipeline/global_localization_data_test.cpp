// Global localization on a map built by a robot (data/malaga_room_map, docs/algorithms.md 7):
// simulated scans from random free poses, localized from no prior; and the dense and walk forms on
// it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "data_dir.hpp"
#include "intgrid/experiments/global_localization_trials.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/simulation/simulator.hpp"

using namespace intgrid::core;

using namespace intgrid::localization;
using namespace intgrid::simulation;
using namespace intgrid::experiments;
using namespace intgrid::io;

namespace intgrid {
namespace {

const std::string kData = test::data_dir();
constexpr double kPi = std::numbers::pi;

GlobalLocConfig room_config() {
  GlobalLocConfig c;
  c.pose_res = 0.2;
  c.headings = 64;
  c.sensor.sigma = 0.03;
  c.sensor.max_range = 8.0;
  return c;
}

// 20 random free poses, 60 readings all round reaching 8 m, 3 cm noise; pose grid 0.2 m x 64
// headings (140 x 130 x 64 = 1.16 M pose cells).
TEST(GlobalLocalizationData, RoomMapLocalizesSimulatedScans) {
  const RosMap map = read_ros_map(kData + "/malaga_room_map.yaml");
  const LocalizationMap lmap(map.grid, map.occupied_thresh, map.free_thresh, room_config());
  SensorConfig sensor = lidar_sensor(60, 2.0 * kPi, 8.0);
  sensor.occupied_threshold = map.occupied_thresh;
  int successes[4] = {};
  constexpr int kPoses = 20;
  const int methods = 4;
  for (int n = 0; n < kPoses; ++n) {
    SimRandom random(700 + std::uint64_t(n));
    const Pose2 truth = random_candidate_pose(lmap, random);
    const Scan scan = simulate_scan(map.grid, sensor, RangeNoiseConfig{0.03, 0.0, 0.0}, truth,
                                    900 + std::uint64_t(n));
    const std::vector<RangeReading> readings = readings_of(scan, 0, lmap.config().sensor.max_range);
    for (int m = 0; m < methods; ++m) {
      const GlobalEstimate e = localize_global(lmap, readings, Pose2{}, GlobalMethod(m));
      const double position = std::hypot(e.robot.x - truth.x, e.robot.y - truth.y);
      const double heading = std::abs(wrap_angle(e.robot.theta - truth.theta));
      ASSERT_GE(readings.size(), 50u);
      const bool ok =
          position <= 2.0 * lmap.config().pose_res && heading <= 2.0 * lmap.heading_bin() + 1e-9;
      successes[m] += ok;
    }
  }
  // Measured 20/20 for every method (pose grid, Markov, mixture, likelihood field): the room is
  // far less symmetric than the procedural floor. Success: within 2 pose cells and 2 bins.
  for (int m = 0; m < methods; ++m) EXPECT_GE(successes[m], kPoses - 1) << "method " << m;
}

TEST(GlobalLocalizationData, DenseAndWalkFormsAgreeOnTheRoomMap) {
  const RosMap map = read_ros_map(kData + "/malaga_room_map.yaml");
  const LocalizationMap lmap(map.grid, map.occupied_thresh, map.free_thresh, room_config());
  std::vector<std::int32_t> dense(lmap.pose_cells(), 0), walk(lmap.pose_cells(), 0);
  SimRandom random(5);
  for (int n = 0; n < 20; ++n) {
    const ReadingClaims claims =
        lmap.claims({random.uniform(0.05, 8.0), random.uniform(-kPi, kPi)});
    lmap.add_reading_dense(claims, dense);
    lmap.add_reading_walk(claims, walk);
  }
  EXPECT_EQ(dense, walk);
  std::size_t nonzero = 0;
  for (const std::int32_t v : dense) nonzero += v != 0;
  EXPECT_GT(nonzero, lmap.candidate_cells() / 2);
}

}  // namespace
}  // namespace intgrid
