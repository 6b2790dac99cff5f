// Trajectory error against a reference: the absolute trajectory error (ATE) over the poses that
// share a timestamp, in the common frame of both logs (no alignment: both start from the log's
// first pose).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "intgrid/slam/log_run.hpp"

namespace intgrid::slam {

struct TrajectoryError {
  std::size_t matched = 0;  // poses with a reference at the same time (within 1 ms)
  double rmse = 0.0;        // metres, position only
  double max = 0.0;
  double mean_heading = 0.0;  // radians, mean absolute heading error
};

// Throws std::invalid_argument if no pose matches a reference time.
TrajectoryError absolute_trajectory_error(std::span<const TimedPose> estimate,
                                          std::span<const TimedPose> reference);

// The robot poses of a log's scans, with their times.
std::vector<TimedPose> scan_poses(const core::Log& log);

}  // namespace intgrid::slam
