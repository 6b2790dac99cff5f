// Range noise.
#include "intgrid/simulation/simulator.hpp"

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

void check_range_noise(const RangeNoiseConfig& c) {
  require_non_negative(c.sigma, "noise.sigma");
  require_probability(c.dropout, "noise.dropout");
  require_probability(c.contamination, "noise.contamination");
}

double corrupt_range(double true_range, double max_range, const RangeNoiseConfig& c,
                     SimRandom& random) {
  const double n = random.normal();
  const double u_dropout = random.uniform();
  const double u_contamination = random.uniform();
  const double u_value = random.uniform_open();
  if (u_dropout < c.dropout) return 0.0;
  if (u_contamination < c.contamination) {
    const double z = u_value * max_range;
    return z < max_range ? z : std::nextafter(max_range, 0.0);
  }
  if (!(true_range < max_range)) return 0.0;
  const double z = true_range + c.sigma * n;
  return z > 0.0 && z < max_range ? z : 0.0;
}

core::Scan simulate_scan(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                         const RangeNoiseConfig& noise, const core::Pose2& robot,
                         SimRandom& random) {
  check_range_noise(noise);
  core::Scan scan;
  scan.robot = robot;
  scan.sensor_mount = sensor.mount;
  scan.angle0 = sensor.angle0;
  scan.dangle = sensor.dangle;
  scan.max_range = sensor.max_range;
  scan.ranges = true_ranges(world, sensor, robot);
  for (double& r : scan.ranges) r = corrupt_range(r, sensor.max_range, noise, random);
  return scan;
}

core::Scan simulate_scan(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                         const RangeNoiseConfig& noise, const core::Pose2& robot,
                         std::uint64_t seed) {
  SimRandom random(seed);
  return simulate_scan(world, sensor, noise, robot, random);
}

}  // namespace intgrid::simulation
