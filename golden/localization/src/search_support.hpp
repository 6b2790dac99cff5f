// What global_localization.cpp and pose_search.cpp share, not part of the module's interface.
#pragma once

#include <span>
#include <vector>

#include "intgrid/core/types.hpp"
#include "intgrid/localization/global_localization.hpp"

namespace intgrid::localization::detail {

// The readings that can be used: finite and positive, below max_range, with a finite bearing.
std::vector<RangeReading> usable_readings(std::span<const RangeReading> readings, double max_range);

// robot = sensor (+) mount^-1 (rule 3), heading wrapped.
inline core::Pose2 robot_of(const core::Pose2& sensor, const core::Pose2& sensor_mount) {
  core::Pose2 robot = core::compose(sensor, core::relative(sensor_mount, core::Pose2{}));
  robot.theta = core::wrap_angle(robot.theta);
  return robot;
}

// A candidate-layout grid laid out as LocalizationMap::index(), `outside` on non-candidates.
template <class Score>
std::vector<Score> in_pose_layout(const LocalizationMap& map, std::span<const Score> grid,
                                  Score outside) {
  std::vector<Score> out(map.pose_cells(), outside);
  for (std::size_t q = 0; q < grid.size(); ++q) {
    const auto [i, j, k] = map.candidate_cell(q);
    out[map.index(i, j, k)] = grid[q];
  }
  return out;
}

}  // namespace intgrid::localization::detail
