// The per-scan path's set-up from a SubmapSlamConfig, shared by SubmapSlam (submap_slam.cpp) and
// MapLocalizer (map_localizer.cpp): the submaps' S_eps codec, the ISM table, the search windows
// and a scan's geometry in the path's units.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "submap_tracking.hpp"

namespace intgrid::slam {

// A pose of the per-scan path (mm, angle units) in metres and radians, and back.
inline core::Pose2 to_pose2(const SlamPose& p) {
  return {static_cast<double>(p.x_mm) * 1e-3, static_cast<double>(p.y_mm) * 1e-3,
          static_cast<double>(p.theta) * core::kRadiansPerAngleUnit};
}
inline SlamPose to_slam_pose(const core::Pose2& p) {
  return {core::millimetres(p.x), core::millimetres(p.y), core::angle_units(p.theta)};
}

// The window of +-window_m and +-degrees on a lattice of cell_mm and step_units, its prior
// prior_m and prior_degrees (0: none).
SearchWindow search_window(double window_m, double degrees, double prior_m, double prior_degrees,
                           std::int32_t cell_mm, std::int32_t step_units);

core::SepsCodec make_codec(const SubmapSlamConfig& c);

// The ISM's values for the submaps' cells: S_eps indices, or their unquantized log-odds.
template <class Cell>
core::IsmTable<Cell> make_table(const SubmapSlamConfig& c, const core::SepsCodec& codec);
template <>
core::IsmTable<std::int8_t> make_table(const SubmapSlamConfig& c, const core::SepsCodec& codec);
template <>
core::IsmTable<LogOdds> make_table(const SubmapSlamConfig& c, const core::SepsCodec& codec);

TrackerSetup make_tracker_setup(const SubmapSlamConfig& c, const core::SepsCodec& codec);

// The scan geometries seen last, most recent first, each with its form in the path's units.
using RecentSensors = std::vector<std::pair<core::Scan, std::shared_ptr<const SlamSensor>>>;
inline constexpr std::size_t kRecentSensors = 8;

// scan's geometry (bearings, mount) in the path's units, shared by the scans that state the same
// one: looked up among `recent` (an interlaced laser alternates two), else made and put in front,
// the oldest of more than kRecentSensors let go. Throws std::invalid_argument, naming label, for
// a scan of no ranges or more than 100000, or a sensor mounted more than 100 m from the robot.
std::shared_ptr<const SlamSensor> recent_sensor(RecentSensors& recent, const core::Scan& scan,
                                                const std::string& label);

}  // namespace intgrid::slam
