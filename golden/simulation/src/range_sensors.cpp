// Range sensors: LiDAR and rings of cones, ray cast in a world.
#include "intgrid/simulation/simulator.hpp"

#include <limits>
#include <stdexcept>

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

SensorConfig lidar_sensor(std::size_t beams, double fov, double max_range) {
  SensorConfig s;
  s.kind = SensorKind::lidar;
  s.beams = beams;
  s.max_range = max_range;
  if (beams <= 1) {
    s.angle0 = 0.0;
    s.dangle = 0.0;
  } else if (fov >= kTwoPi) {
    s.angle0 = -kPi;
    s.dangle = kTwoPi / static_cast<double>(beams);
  } else {
    s.angle0 = -0.5 * fov;
    s.dangle = fov / static_cast<double>(beams - 1);
  }
  return s;
}

SensorConfig cone_ring_sensor(std::size_t cones, double cone_fov, double max_range) {
  SensorConfig s;
  s.kind = SensorKind::cone;
  s.beams = cones;
  s.angle0 = 0.0;
  s.dangle = cones == 0 ? 0.0 : kTwoPi / static_cast<double>(cones);
  s.cone_fov = cone_fov;
  s.max_range = max_range;
  return s;
}

void check_sensor_config(const SensorConfig& c) {
  if (c.beams == 0) fail_field("sensor.beams", "must be at least 1");
  if (c.beams > 100000) fail_field("sensor.beams", "must be at most 100000");
  require_finite(c.angle0, "sensor.angle0");
  require_finite(c.dangle, "sensor.dangle");
  require_positive(c.max_range, "sensor.max_range");
  require_finite_pose(c.mount, "sensor.mount");
  if (!(c.occupied_threshold > 0.0 && c.occupied_threshold <= 1.0))
    fail_field("sensor.occupied_threshold",
               "must be in (0, 1], got " + number(c.occupied_threshold));
  if (c.kind == SensorKind::cone) {
    if (!(c.cone_fov > 0.0 && c.cone_fov < kPi))
      fail_field("sensor.cone_fov", "must be in (0, pi) rad, got " + number(c.cone_fov));
    if (c.rays_per_cone > 100000) fail_field("sensor.rays_per_cone", "must be at most 100000");
  }
}

double ray_cast(const core::ProbabilityGrid& world, double x, double y, double angle,
                double max_range, double occupied_threshold) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(angle) || !(max_range >= 0.0) ||
      !std::isfinite(max_range))
    core::fail<std::invalid_argument>("ray_cast: the start, angle and max_range must be finite");
  const core::GridGeometry& g = world.geometry;
  const double res = g.resolution;
  const double dx = std::cos(angle), dy = std::sin(angle);
  // The part [t0, t1] of the ray inside the grid's box and within max_range.
  double t0 = 0.0, t1 = max_range;
  const auto clip = [&](double p, double d, double lo, double hi) {
    if (d == 0.0) return p >= lo && p <= hi;
    double a = (lo - p) / d, b = (hi - p) / d;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    return true;
  };
  if (!clip(x, dx, g.origin_x, g.origin_x + g.width * res) ||
      !clip(y, dy, g.origin_y, g.origin_y + g.height * res) || t0 > t1)
    return max_range;
  const auto occupied = [&](int ix, int iy) {
    return g.contains(ix, iy) && world.at(ix, iy) >= occupied_threshold;
  };
  int ix = std::clamp(g.cell_x(x + t0 * dx), 0, g.width - 1);
  int iy = std::clamp(g.cell_y(y + t0 * dy), 0, g.height - 1);
  const int step_x = dx > 0.0 ? 1 : -1, step_y = dy > 0.0 ? 1 : -1;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  // The distance at which the ray crosses the boundary of column ix (row iy) it goes toward.
  const auto next_x = [&](int column) {
    if (dx == 0.0) return kNever;
    return (g.origin_x + (dx > 0.0 ? column + 1 : column) * res - x) / dx;
  };
  const auto next_y = [&](int row) {
    if (dy == 0.0) return kNever;
    return (g.origin_y + (dy > 0.0 ? row + 1 : row) * res - y) / dy;
  };
  double t_enter = t0;
  double t_x = next_x(ix), t_y = next_y(iy);
  for (;;) {
    if (occupied(ix, iy)) return t_enter < max_range ? t_enter : max_range;
    if (t_x == t_y) {  // through a corner: the ray touches both cells beside it
      t_enter = t_x;
      if (t_enter > t1) return max_range;
      if (occupied(ix + step_x, iy) || occupied(ix, iy + step_y))
        return t_enter < max_range ? t_enter : max_range;
      ix += step_x;
      iy += step_y;
      t_x = next_x(ix);
      t_y = next_y(iy);
    } else if (t_x < t_y) {
      t_enter = t_x;
      ix += step_x;
      t_x = next_x(ix);
    } else {
      t_enter = t_y;
      iy += step_y;
      t_y = next_y(iy);
    }
    if (t_enter > t1 || !g.contains(ix, iy)) return max_range;
  }
}

std::vector<double> true_ranges(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                                const core::Pose2& robot) {
  check_sensor_config(sensor);
  check_world(world);
  require_finite_pose(robot, "robot pose");
  const core::Pose2 s = core::compose(robot, sensor.mount);
  std::vector<double> ranges(sensor.beams);
  std::size_t rays = 1;
  if (sensor.kind == SensorKind::cone) {
    rays = sensor.rays_per_cone;
    if (rays == 0) {
      const double needed =
          std::ceil(sensor.cone_fov * sensor.max_range / world.geometry.resolution) + 1.0;
      rays = static_cast<std::size_t>(std::clamp(needed, 2.0, 100000.0));
    }
  }
  for (std::size_t i = 0; i < sensor.beams; ++i) {
    // The bearing as a Scan computes it, so that a reader of the log finds the same ray.
    const double axis = s.theta + (sensor.angle0 + static_cast<double>(i) * sensor.dangle);
    if (sensor.kind == SensorKind::lidar) {
      ranges[i] = ray_cast(world, s.x, s.y, axis, sensor.max_range, sensor.occupied_threshold);
      continue;
    }
    double nearest = sensor.max_range;
    for (std::size_t k = 0; k < rays; ++k) {
      const double offset =
          rays == 1
              ? 0.0
              : sensor.cone_fov * (static_cast<double>(k) / static_cast<double>(rays - 1) - 0.5);
      nearest = std::min(nearest, ray_cast(world, s.x, s.y, axis + offset, sensor.max_range,
                                           sensor.occupied_threshold));
    }
    ranges[i] = nearest;
  }
  return ranges;
}

}  // namespace intgrid::simulation
