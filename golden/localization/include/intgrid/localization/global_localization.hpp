// Global localization with pose occupancy grids (docs/algorithms.md 7, thesis chapter 4), and the
// baselines a user would pick instead, on the same pose grid and readings.
//
// The robot knows the map, not its pose. The pose grid covers the map at pose_res over
// `headings` heading bins; its cells hold the SENSOR's pose (rule 3): the estimate steps back
// by the mounting pose to report the robot's. Rays run along a family of parallel digital
// lines per direction bin (one line through every pose cell, so the lines partition the grid),
// which makes the forward "first hit from a pose" and the backward "walk from a source" two
// exact views of one relation: the dense form and the walk form give identical grids.
//
// One concept a header: global_loc_config.hpp (the settings), range_reading.hpp,
// localization_map.hpp (the map and the readings' claims), markov_localization.hpp (the
// baselines), pose_search.hpp, pose_tracker.hpp; this one localizes from no prior.
#pragma once

#include <span>

#include "intgrid/core/types.hpp"
#include "intgrid/localization/global_loc_config.hpp"
#include "intgrid/localization/localization_map.hpp"
#include "intgrid/localization/markov_localization.hpp"
#include "intgrid/localization/pose_search.hpp"
#include "intgrid/localization/pose_tracker.hpp"
#include "intgrid/localization/range_reading.hpp"

namespace intgrid::localization {

// Localizes one set of readings from no prior. Readings that are not finite and positive, at or
// past max_range, or with a non-finite bearing are not used. `scores`, when given, receives every
// cell's. Baselines: the sensor estimate is the best candidate cell's pose (pose_of), the mean of
// the tied ones (headings by circular mean). The pose grid: search_pose_grid's best hypothesis with
// the readings as both screening and verification readings, one thread (ties is then the count of
// cells at the best score; the estimate, the mean of those around the first of them).
// robot = compose(sensor, inverse of sensor_mount).
GlobalEstimate localize_global(const LocalizationMap& map, std::span<const RangeReading> readings,
                               const core::Pose2& sensor_mount, GlobalMethod method,
                               PoseScores* scores = nullptr);

// The same for one scan, in SI units as every algorithm takes it: `beams` of its usable readings
// (readings_of; all when beams <= 0), with the scan's sensor mount.
GlobalEstimate localize_scan(const LocalizationMap& map, const core::Scan& scan, int beams,
                             GlobalMethod method, PoseScores* scores = nullptr);

}  // namespace intgrid::localization
