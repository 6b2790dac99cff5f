// Obstacles the map does not hold.
#include "intgrid/simulation/simulator.hpp"

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

void check_obstacle_config(const ObstacleConfig& c) {
  if (c.count > 1'000'000) fail_field("obstacles.count", "must be at most 10^6");
  require_positive(c.min_diameter, "obstacles.min_diameter");
  require_positive(c.max_diameter, "obstacles.max_diameter");
  if (c.min_diameter > c.max_diameter)
    fail_field("obstacles.min_diameter", "must not exceed max_diameter");
  require_non_negative(c.clearance, "obstacles.clearance");
  if (c.large_distance) {
    require_non_negative(*c.large_distance, "obstacles.large_distance");
    require_positive(c.large_diameter, "obstacles.large_diameter");
  }
}

std::vector<Disc> place_obstacles(const core::ProbabilityGrid& world,
                                  const std::vector<core::Pose2>& truth, const ObstacleConfig& c,
                                  double free_threshold, SimRandom& random) {
  check_obstacle_config(c);
  check_world(world);
  const core::GridGeometry& g = world.geometry;
  std::vector<Disc> discs;
  if (c.count > 0) {
    std::vector<std::size_t> free_cells;
    for (std::size_t i = 0; i < g.size(); ++i)
      if (is_free(world.cells[i], free_threshold)) free_cells.push_back(i);
    if (free_cells.empty())
      fail_field("obstacles.count", "cannot be placed: the world has no free cell");
    const double half_diagonal = 0.5 * kSqrt2 * g.resolution;
    for (std::size_t k = 0; k < c.count; ++k) {
      bool placed = false;
      for (int attempt = 0; attempt < 1000 && !placed; ++attempt) {
        const std::size_t cell = free_cells[random.below(free_cells.size())];
        const int cx = static_cast<int>(cell % g.width), cy = static_cast<int>(cell / g.width);
        const double u = random.uniform(), v = random.uniform(), w = random.uniform();
        const Disc d{g.centre_x(cx) + (u - 0.5) * g.resolution,
                     g.centre_y(cy) + (v - 0.5) * g.resolution,
                     0.5 * (c.min_diameter + w * (c.max_diameter - c.min_diameter))};
        const double keep = c.clearance + d.radius + half_diagonal;
        const bool clear = std::all_of(truth.begin(), truth.end(), [&](const core::Pose2& p) {
          return std::hypot(p.x - d.x, p.y - d.y) >= keep;
        });
        if (!clear) continue;
        const bool inside = d.x - d.radius >= g.origin_x && d.y - d.radius >= g.origin_y &&
                            d.x + d.radius <= g.origin_x + g.width * g.resolution &&
                            d.y + d.radius <= g.origin_y + g.height * g.resolution;
        if (!inside) continue;
        const std::vector<std::pair<int, int>> cells = disc_cells(g, d);
        const bool in_free_space = std::all_of(cells.begin(), cells.end(), [&](auto ij) {
          return is_free(world.at(ij.first, ij.second), free_threshold);
        });
        if (!in_free_space) continue;
        discs.push_back(d);
        placed = true;
      }
      if (!placed)
        fail_field("obstacles.count", "cannot be placed: only " + std::to_string(discs.size()) +
                                          " of " + std::to_string(c.count) +
                                          " obstacles fit in free space away from the trajectory");
    }
  }
  if (c.large_distance) {
    if (truth.empty()) fail_field("obstacles.large_distance", "needs a true pose to measure from");
    const core::Pose2& p = truth.front();
    const double r = 0.5 * c.large_diameter;
    const double reach = *c.large_distance + r;
    discs.push_back({p.x + reach * std::cos(p.theta), p.y + reach * std::sin(p.theta), r});
  }
  return discs;
}

void add_obstacles(core::ProbabilityGrid& world, const std::vector<Disc>& discs) {
  for (const Disc& d : discs)
    for (const auto& [ix, iy] : disc_cells(world.geometry, d)) world.at(ix, iy) = 1.0;
}

}  // namespace intgrid::simulation
