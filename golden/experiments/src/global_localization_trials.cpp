#include "intgrid/experiments/global_localization_trials.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"

namespace intgrid::experiments {
namespace {

// The map's cells within max_range + one cell of (x, y), as a grid of its own (same resolution,
// origin on the map's lattice), clipped to the map.
core::ProbabilityGrid window_around(const core::ProbabilityGrid& map, double x, double y,
                                    double reach) {
  const core::GridGeometry& g = map.geometry;
  const int x0 = std::max(0, g.cell_x(x - reach) - 1);
  const int y0 = std::max(0, g.cell_y(y - reach) - 1);
  const int x1 = std::min(g.width - 1, g.cell_x(x + reach) + 1);
  const int y1 = std::min(g.height - 1, g.cell_y(y + reach) + 1);
  if (x1 < x0 || y1 < y0) core::fail<std::invalid_argument>("the true pose lies outside the map");
  core::GridGeometry w{x1 - x0 + 1, y1 - y0 + 1, g.resolution, g.origin_x + x0 * g.resolution,
                       g.origin_y + y0 * g.resolution};
  core::ProbabilityGrid out(w, 0.5);
  for (int iy = 0; iy < w.height; ++iy)
    for (int ix = 0; ix < w.width; ++ix) out.at(ix, iy) = map.at(x0 + ix, y0 + iy);
  return out;
}

}  // namespace

GlobalTrialWorld::GlobalTrialWorld(const core::ProbabilityGrid& map, double occupied_threshold,
                                   double free_threshold, double clearance)
    : map_(&map),
      occupied_threshold_(occupied_threshold),
      free_threshold_(free_threshold),
      clearance_(clearance) {
  core::check_geometry(map.geometry);
  if (!(occupied_threshold > 0.0 && occupied_threshold <= 1.0))
    core::fail<std::invalid_argument>("occupied_threshold must be in (0, 1]");
  if (!(free_threshold > 0.0 && free_threshold <= occupied_threshold))
    core::fail<std::invalid_argument>("free_threshold must be in (0, occupied_threshold]");
  if (!(clearance >= 0.0) || !std::isfinite(clearance))
    core::fail<std::invalid_argument>("clearance must be a finite distance >= 0");
  const core::Grid<double> distance = simulation::clearance_map(map, free_threshold);
  for (std::size_t i = 0; i < distance.cells.size(); ++i) {
    const double p = map.cells[i];
    if (p < free_threshold && distance.cells[i] >= clearance && distance.cells[i] > 0.0)
      cells_.push_back(i);
  }
  if (cells_.empty())
    core::fail<std::invalid_argument>("the map has no free cell " + core::number_text(clearance) +
                                      " m from every non-free cell");
}

core::Pose2 GlobalTrialWorld::random_pose(simulation::SimRandom& random) const {
  const core::GridGeometry& g = map_->geometry;
  const std::size_t cell = cells_[random.below(cells_.size())];
  const int ix = static_cast<int>(cell % static_cast<std::size_t>(g.width));
  const int iy = static_cast<int>(cell / static_cast<std::size_t>(g.width));
  const double x = g.origin_x + (ix + random.uniform()) * g.resolution;
  const double y = g.origin_y + (iy + random.uniform()) * g.resolution;
  const double theta = random.uniform(-std::numbers::pi, std::numbers::pi);
  return {x, y, theta};
}

core::Pose2 random_candidate_pose(const localization::LocalizationMap& map,
                                  simulation::SimRandom& random) {
  if (map.width() < 3 || map.height() < 3)
    core::fail<std::invalid_argument>("the pose grid is smaller than 3 x 3 cells");
  while (true) {
    const int i = 1 + static_cast<int>(random.below(std::uint64_t(map.width() - 2)));
    const int j = 1 + static_cast<int>(random.below(std::uint64_t(map.height() - 2)));
    bool clear = true;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) clear = clear && map.is_candidate(i + di, j + dj);
    if (!clear) continue;
    const core::Pose2 centre = map.pose_of(i, j, 0);
    const double r = map.config().pose_res;
    return {centre.x + r * (random.uniform() - 0.5), centre.y + r * (random.uniform() - 0.5),
            random.uniform(-std::numbers::pi, std::numbers::pi)};
  }
}

void check_global_trial_conditions(const GlobalTrialConditions& c) {
  if (c.readings == 0 || c.readings > 100000)
    core::fail<std::invalid_argument>("readings must be in 1..100000");
  if (!(c.fov > 0.0 && c.fov <= 2.0 * std::numbers::pi))
    core::fail<std::invalid_argument>("fov must be in (0, 2 pi]");
  if (!(c.max_range > 0.0) || !std::isfinite(c.max_range))
    core::fail<std::invalid_argument>("max_range must be a positive finite distance");
  if (!(c.noise >= 0.0) || !std::isfinite(c.noise))
    core::fail<std::invalid_argument>("noise must be a finite distance >= 0");
  if (!(c.contamination >= 0.0 && c.contamination <= 1.0))
    core::fail<std::invalid_argument>("contamination must be in [0, 1]");
  if (c.obstacles > 1000000) core::fail<std::invalid_argument>("obstacles must be at most 10^6");
  if (c.large_obstacle && (!(*c.large_obstacle >= 0.0) || !std::isfinite(*c.large_obstacle)))
    core::fail<std::invalid_argument>("large_obstacle must be a finite distance >= 0");
  if (!(c.obstacle_clearance >= 0.0) || !std::isfinite(c.obstacle_clearance))
    core::fail<std::invalid_argument>("obstacle_clearance must be a finite distance >= 0");
}

GlobalTrial simulate_global_trial(const GlobalTrialWorld& world, const GlobalTrialConditions& c,
                                  const core::Pose2& truth, std::uint64_t seed) {
  check_global_trial_conditions(c);
  if (!std::isfinite(truth.x) || !std::isfinite(truth.y) || !std::isfinite(truth.theta))
    core::fail<std::invalid_argument>("the true pose must be finite");
  const core::ProbabilityGrid& map = world.map();
  core::ProbabilityGrid sensed =
      window_around(map, truth.x, truth.y, c.max_range + map.geometry.resolution);

  GlobalTrial trial;
  trial.truth = truth;
  if (c.obstacles > 0 || c.large_obstacle) {
    simulation::ObstacleConfig o;
    o.count = c.obstacles;
    o.clearance = c.obstacle_clearance;
    o.large_distance = c.large_obstacle;
    simulation::SimRandom obstacle_random(simulation::derive_seed(seed, 1));
    trial.obstacles =
        simulation::place_obstacles(sensed, {truth}, o, world.free_threshold(), obstacle_random);
    simulation::add_obstacles(sensed, trial.obstacles);
  }

  simulation::SensorConfig sensor = simulation::lidar_sensor(c.readings, c.fov, c.max_range);
  sensor.occupied_threshold = world.occupied_threshold();
  simulation::RangeNoiseConfig noise;
  noise.sigma = c.noise;
  noise.contamination = c.contamination;
  simulation::SimRandom noise_random(simulation::derive_seed(seed, 2));
  trial.scan = simulation::simulate_scan(sensed, sensor, noise, truth, noise_random);
  trial.readings = localization::readings_of(trial.scan, 0, c.max_range);
  return trial;
}

GlobalTrialError global_trial_error(const core::Pose2& truth, const core::Pose2& estimate,
                                    double position_tolerance, double heading_tolerance) {
  GlobalTrialError e;
  e.position = std::hypot(estimate.x - truth.x, estimate.y - truth.y);
  e.heading = std::abs(core::wrap_angle(estimate.theta - truth.theta));
  e.success = e.position <= position_tolerance && e.heading <= heading_tolerance;
  return e;
}

}  // namespace intgrid::experiments
