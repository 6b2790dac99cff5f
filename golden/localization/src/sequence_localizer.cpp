#include "intgrid/localization/sequence_localizer.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "intgrid/core/failure.hpp"
#include "intgrid/localization/range_reading.hpp"

namespace intgrid::localization {

void check_sequence_options(const SequenceOptions& options) {
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!non_negative(options.step_position))
    core::fail<std::invalid_argument>("step_position must be finite and non-negative");
  if (!non_negative(options.step_heading))
    core::fail<std::invalid_argument>("step_heading must be finite and non-negative");
}

SequenceLocalizer::SequenceLocalizer(const LocalizationMap& map, const PoseSearchOptions& search,
                                     const SequenceOptions& options)
    : map_(&map), options_(options), tracker_(map, search, options.max_scans) {
  check_sequence_options(options);
}

std::optional<PoseSearchResult> SequenceLocalizer::offer(const core::Scan& scan) {
  if (done_) return std::nullopt;
  const core::Pose2 sensor = scan.sensor_pose();
  core::Pose2 motion{};
  if (last_sensor_) {
    motion = core::relative(*last_sensor_, sensor);
    if (std::hypot(motion.x, motion.y) < options_.step_position &&
        std::abs(core::wrap_angle(motion.theta)) < options_.step_heading)
      return std::nullopt;
  }
  const double max_range = map_->config().sensor.max_range;
  const std::vector<RangeReading> screening = readings_of(scan, options_.beams, max_range);
  if (screening.empty()) return std::nullopt;
  tracker_.add_scan(screening, readings_of(scan, options_.verify_beams, max_range), motion);
  last_sensor_ = sensor;
  PoseSearchResult found = tracker_.search(scan.sensor_mount);
  done_ = !found.ambiguous || tracker_.scans() >= tracker_.max_scans();
  return found;
}

}  // namespace intgrid::localization
