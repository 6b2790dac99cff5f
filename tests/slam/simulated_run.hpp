// Simulated runs for the submap SLAM's tests: a robot driven along true poses through a world,
// its log with noisy (and, if asked, biased) odometry beside the truth.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "intgrid/core/types.hpp"
#include "intgrid/simulation/simulator.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::slam::test {

// A simulated log and the true poses of its scans.
struct SimulatedRun {
  core::Log log;
  std::vector<TimedPose> truth;
};

// Sets every cell of world whose centre lies inside (x0, x1) x (y0, y1) (m) to value: a drawn
// world's rooms (0, free) and obstacles (1).
inline void fill_rectangle(core::ProbabilityGrid& world, double x0, double y0, double x1, double y1,
                           double value) {
  for (int iy = 0; iy < world.geometry.height; ++iy)
    for (int ix = 0; ix < world.geometry.width; ++ix) {
      const double x = world.geometry.centre_x(ix), y = world.geometry.centre_y(iy);
      if (x > x0 && x < x1 && y > y0 && y < y1) world.at(ix, iy) = value;
    }
}

// A robot driven along truth in world, a scan every 0.2 s: the log carries the default noisy
// odometry (seeded odometry_seed), each of its turns reported turn_scale times as large (a wheel
// base calibrated wrong: a heading bias) and each of its moves travel_scale times as long (a wheel
// radius calibrated wrong), and the sensor's noisy ranges (seeded range_seed).
inline SimulatedRun record_run(const core::ProbabilityGrid& world,
                               const std::vector<core::Pose2>& truth, std::uint64_t odometry_seed,
                               const simulation::SensorConfig& sensor, std::uint64_t range_seed,
                               double turn_scale = 1.0, double travel_scale = 1.0) {
  simulation::SimRandom odometry_random(odometry_seed);
  const std::vector<core::Pose2> unbiased =
      simulation::noisy_odometry(truth, simulation::OdometryNoiseConfig{}, odometry_random);
  std::vector<core::Pose2> odometry{unbiased.front()};
  for (std::size_t i = 1; i < unbiased.size(); ++i) {
    core::Pose2 step = core::relative(unbiased[i - 1], unbiased[i]);
    step.theta = std::remainder(step.theta, 2 * std::numbers::pi) * turn_scale;
    step.x *= travel_scale;
    step.y *= travel_scale;
    odometry.push_back(core::compose(odometry.back(), step));
  }
  simulation::SimRandom range_random(range_seed);
  SimulatedRun run;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    core::Scan scan = simulation::simulate_scan(world, sensor, {}, truth[i], range_random);
    scan.t = 0.2 * static_cast<double>(i);
    scan.robot = odometry[i];
    run.truth.push_back({scan.t, truth[i]});
    run.log.scans.push_back(std::move(scan));
  }
  return run;
}

}  // namespace intgrid::slam::test
