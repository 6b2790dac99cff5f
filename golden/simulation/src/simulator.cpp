// The simulation: a world, a trajectory, odometry and scans, from one seed.
#include "intgrid/simulation/simulator.hpp"

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

void check_simulation_config(const SimulationConfig& c) {
  check_trajectory_config(c.trajectory);
  check_odometry_noise(c.odometry);
  check_sensor_config(c.sensor);
  check_range_noise(c.noise);
  check_obstacle_config(c.obstacles);
  require_finite(c.start_time, "start_time");
  if (c.true_poses.size() > 10'000'000) fail_field("true_poses", "must hold at most 10^7 poses");
  for (std::size_t i = 0; i < c.true_poses.size(); ++i)
    require_finite_pose(c.true_poses[i], "true_poses[" + std::to_string(i) + "]");
  for (const Point2& p : c.route)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) fail_field("route", "points must be finite");
  if (c.trajectory.free_threshold > c.sensor.occupied_threshold)
    fail_field("trajectory.free_threshold",
               "must not exceed sensor.occupied_threshold (free cells would stop rays)");
}

Simulation simulate(const core::ProbabilityGrid& world, const SimulationConfig& c,
                    std::uint64_t seed) {
  check_simulation_config(c);
  check_world(world);
  std::vector<core::Pose2> truth;
  if (!c.true_poses.empty()) {
    truth = c.true_poses;
  } else if (!c.route.empty()) {
    truth = follow_route(c.route, true, c.trajectory);
  } else {
    truth = random_trajectory(world, c.trajectory, derive_seed(seed, 1));
  }
  Simulation sim;
  sim.world = world;
  SimRandom obstacle_random(derive_seed(seed, 2));
  sim.obstacles =
      place_obstacles(world, truth, c.obstacles, c.trajectory.free_threshold, obstacle_random);
  sim.sensed_world = world;
  add_obstacles(sim.sensed_world, sim.obstacles);
  SimRandom odometry_random(derive_seed(seed, 3));
  const std::vector<core::Pose2> odometry = noisy_odometry(truth, c.odometry, odometry_random);
  SimRandom noise_random(derive_seed(seed, 4));
  sim.log.scans.reserve(truth.size());
  sim.log.odometry.reserve(truth.size());
  sim.truth.scans.reserve(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double t = c.start_time + static_cast<double>(i) * c.trajectory.scan_period;
    core::Scan scan = simulate_scan(sim.sensed_world, c.sensor, c.noise, truth[i], noise_random);
    scan.t = t;
    sim.truth.scans.push_back(scan);
    scan.robot = odometry[i];
    sim.log.scans.push_back(std::move(scan));
    sim.log.odometry.push_back({t, odometry[i]});
  }
  return sim;
}

}  // namespace intgrid::simulation
