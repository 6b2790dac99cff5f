// What the jobs that estimate a trajectory (`slam`, `localize`) write and report alike: the
// trajectory file, the ATE in metrics.json, the positions drawn on a map, the process's peak
// memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "intgrid/core/types.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {

// {"rmse_m", "max_m", "matched", "mean_heading_error_deg"}.
nlohmann::json error_json(const slam::TrajectoryError& e);

// "t x y theta" lines (s, m, m, rad) under a header line naming `what` the poses are, atomically.
void write_trajectory(const std::filesystem::path& file, const std::vector<slam::TimedPose>& poses,
                      const std::string& what);

std::vector<core::Pose2> positions(const std::vector<slam::TimedPose>& poses);

// The peak resident set of this process so far (bytes; Linux reports ru_maxrss in KiB).
std::size_t peak_memory_bytes();

}  // namespace intgrid::cli
