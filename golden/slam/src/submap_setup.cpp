// The per-scan path's set-up from a SubmapSlamConfig (submap_setup.hpp).
#include "submap_setup.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/slam/grid_slam.hpp"

namespace intgrid::slam {

using core::angle_units;
using core::millimetres;
using core::radians;

namespace {

std::int32_t ism_step_mm(const SubmapSlamConfig& c) {
  return std::max<std::int32_t>(1, static_cast<std::int32_t>(millimetres(c.cell)) / 8);
}

}  // namespace

SearchWindow search_window(double window_m, double degrees, double prior_m, double prior_degrees,
                           std::int32_t cell_mm, std::int32_t step_units) {
  SearchWindow w;
  w.cells = static_cast<int>(std::ceil(window_m * 1000.0 / cell_mm - 1e-9));
  w.step_units = step_units;
  w.steps = static_cast<int>(
      std::ceil(static_cast<double>(angle_units(radians(degrees))) / step_units - 1e-9));
  w.prior_xy_mm = prior_m > 0.0 ? millimetres(prior_m) : 0;
  w.prior_theta_units = prior_degrees > 0.0 ? angle_units(radians(prior_degrees)) : 0;
  return w;
}

core::SepsCodec make_codec(const SubmapSlamConfig& c) {
  return core::SepsCodec::for_levels(c.map.seps_bits, core::narrow_pmax(c.cell, c.sensor.sigma),
                                     c.map.seps_levels);
}

template <>
core::IsmTable<std::int8_t> make_table(const SubmapSlamConfig& c, const core::SepsCodec& codec) {
  return core::make_index_ism_table(
      core::GaussianBeamModel{c.sensor.sigma, 0.0}, c.cell, codec, ism_step_mm(c),
      static_cast<std::int32_t>(millimetres(c.sensor.max_range)), c.map.empty_divisor);
}

// The exact ISM's log-odds in S_eps steps, bounded as the index table's are by the most one
// reading may claim (p_levels = Pmax, the narrow ISM's bound: the exact ISM's empty cells reach
// probabilities near 0, which one reading must not carry), empty values divided likewise.
template <>
core::IsmTable<LogOdds> make_table(const SubmapSlamConfig& c, const core::SepsCodec& codec) {
  const core::IsmTable<double> p = core::make_probability_ism_table(
      core::GaussianBeamModel{c.sensor.sigma, 0.0}, c.cell, ism_step_mm(c),
      static_cast<std::int32_t>(millimetres(c.sensor.max_range)));
  const double bound = c.map.seps_levels;
  std::vector<LogOdds> values;
  values.reserve(p.values.size());
  for (const double v : p.values) {
    double steps = std::clamp(core::logit(v) / codec.lambda(), -bound, bound);
    if (steps < 0.0) steps /= c.map.empty_divisor;
    values.push_back({steps});
  }
  return core::make_ism_table(p.z_step_mm, p.begin, std::move(values));
}

TrackerSetup make_tracker_setup(const SubmapSlamConfig& c, const core::SepsCodec& codec) {
  TrackerSetup s;
  s.cell_mm = static_cast<std::int32_t>(millimetres(c.cell));
  s.max_range_mm = static_cast<std::int32_t>(millimetres(c.sensor.max_range));
  s.sin_q16 = core::make_sine_table_q16();
  s.max_index = codec.max_index();
  const std::int32_t step = core::kAngleUnitsPerTurn / c.headings;
  const auto& t = c.tracking;
  s.narrow =
      search_window(t.window, t.window_degrees, t.prior_xy, t.prior_degrees, s.cell_mm, step);
  s.wide = search_window(t.wide_window, t.wide_degrees, 0.0, 0.0, s.cell_mm, step);
  s.prior_xy_per_mm_q16 = std::llround(t.prior_xy_per_m * 65536.0);
  s.prior_theta_per_unit_q16 = std::llround(t.prior_degrees_per_degree * 65536.0);
  s.wide_below_permille = std::llround(t.wide_below * 1000.0);
  s.min_hits = t.min_hits;
  s.submap_scans = c.submaps.scans;
  s.handover_scans = c.submaps.handover_scans;
  s.filter_mm = millimetres(c.filter.distance);
  s.filter_units = angle_units(radians(c.filter.degrees));
  s.filter_ms = core::milliseconds(c.filter.seconds);
  s.threads = core::threads_or_every_core(c.threads);
  return s;
}

std::shared_ptr<const SlamSensor> recent_sensor(RecentSensors& recent, const core::Scan& scan,
                                                const std::string& label) {
  for (auto it = recent.begin(); it != recent.end(); ++it)
    if (geometry_difference(scan, it->first) == nullptr) {
      std::rotate(recent.begin(), it, it + 1);
      return recent.front().second;
    }
  const double mount = std::hypot(scan.sensor_mount.x, scan.sensor_mount.y);
  if (!std::isfinite(mount) || mount > 100.0 || !std::isfinite(scan.sensor_mount.theta))
    core::fail<std::invalid_argument>(label +
                                      ": the sensor is mounted more than 100 m from the robot");
  if (scan.ranges.empty() || scan.ranges.size() > 100000)
    core::fail<std::invalid_argument>(label + " has " + std::to_string(scan.ranges.size()) +
                                      " ranges; SLAM takes 1 to 100000");
  auto sensor = std::make_shared<SlamSensor>();
  for (std::size_t i = 0; i < scan.ranges.size(); ++i)
    sensor->bearing.push_back(static_cast<std::int32_t>(angle_units(scan.bearing(i))));
  sensor->mount_x_mm = static_cast<std::int32_t>(millimetres(scan.sensor_mount.x));
  sensor->mount_y_mm = static_cast<std::int32_t>(millimetres(scan.sensor_mount.y));
  sensor->mount_theta = static_cast<std::int32_t>(angle_units(scan.sensor_mount.theta));
  core::Scan key = scan;
  key.ranges.assign(scan.ranges.size(), 0.0);
  recent.insert(recent.begin(), {std::move(key), std::move(sensor)});
  if (recent.size() > kRecentSensors) recent.pop_back();
  return recent.front().second;
}

}  // namespace intgrid::slam
