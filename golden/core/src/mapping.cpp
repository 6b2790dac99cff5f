#include "intgrid/core/mapping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

GridGeometry geometry_covering(std::span<const Scan> scans, double resolution, double margin) {
  if (!(resolution > 0.0) || !std::isfinite(resolution))
    fail<std::invalid_argument>("resolution must be a positive finite number");
  double x_lo = std::numeric_limits<double>::infinity(), y_lo = x_lo;
  double x_hi = -x_lo, y_hi = -x_lo;
  const auto include = [&](double x, double y) {
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
    y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
  };
  bool any_valid = false;
  for (const Scan& scan : scans) {
    const Pose2 sensor = scan.sensor_pose();
    include(sensor.x, sensor.y);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const double z = scan.ranges[i];
      if (classify_range(z, scan.max_range) != RangeClass::valid) continue;
      any_valid = true;
      const double a = sensor.theta + scan.bearing(i);
      include(sensor.x + z * std::cos(a), sensor.y + z * std::sin(a));
    }
  }
  if (!any_valid) fail<std::invalid_argument>("no scan holds a valid reading");
  GridGeometry g;
  g.resolution = resolution;
  g.origin_x = std::floor((x_lo - margin) / resolution) * resolution;
  g.origin_y = std::floor((y_lo - margin) / resolution) * resolution;
  const double width = std::ceil((x_hi + margin - g.origin_x) / resolution);
  const double height = std::ceil((y_hi + margin - g.origin_y) / resolution);
  if (width * height > static_cast<double>(std::size_t{1} << 32) || width > 1e9 || height > 1e9)
    fail<std::invalid_argument>("the grid covering the log would have more than 2^32 cells");
  g.width = static_cast<int>(width);
  g.height = static_cast<int>(height);
  check_geometry(g);
  return g;
}

ProbabilityGrid map_probabilities(std::span<const Scan> scans, const GaussianBeamModel& model,
                                  const GridGeometry& geometry, InsertionStats& stats,
                                  const Progress& progress) {
  check_model(model);
  ProbabilityGrid grid(geometry, 0.5);
  insert_scans(grid, scans, model, stats, {}, progress);
  return grid;
}

void insert_scans(ProbabilityGrid& grid, std::span<const Scan> scans,
                  const GaussianBeamModel& model, InsertionStats& stats, RowBand rows,
                  const Progress& progress) {
  for (std::size_t i = 0; i < scans.size(); ++i) {
    insert_scan(grid, scans[i], model, stats, rows);
    if (progress) progress(i + 1, scans.size());
  }
}

}  // namespace intgrid::core
