// SubmapSlam's per-scan path in the integer arithmetic (S_eps submaps, index sums). Built without
// floating-point registers, as the event-driven SLAM's is; no_floating_point_in_integer_slam
// disassembles it.
#include "submap_tracking.hpp"

namespace intgrid::slam {

ScanPoints scan_points(const core::IntegerRays& rays, const SlamSensor& sensor,
                       std::span<const std::int32_t> range_mm, std::int32_t max_range_mm) {
  ScanPoints points;
  points.x_mm.reserve(range_mm.size());
  points.y_mm.reserve(range_mm.size());
  for (std::size_t b = 0; b < range_mm.size(); ++b) {
    const std::int32_t z = range_mm[b];
    if (z <= 0 || z >= max_range_mm) continue;
    const auto [x, y] = rays.rotate(sensor.mount_theta + sensor.bearing[b], z, 0);
    points.x_mm.push_back(static_cast<std::int32_t>(x + sensor.mount_x_mm));
    points.y_mm.push_back(static_cast<std::int32_t>(y + sensor.mount_y_mm));
  }
  return points;
}

template class LocalTracker<std::int8_t>;

}  // namespace intgrid::slam
