#include "intgrid/slam/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "intgrid/core/failure.hpp"

namespace intgrid::slam {

TrajectoryError absolute_trajectory_error(std::span<const TimedPose> estimate,
                                          std::span<const TimedPose> reference) {
  TrajectoryError e;
  double squares = 0.0, headings = 0.0;
  std::size_t r = 0;
  for (const TimedPose& p : estimate) {
    // Both are in time order: advance the reference to the first time not before p.t - 1 ms.
    while (r < reference.size() && reference[r].t < p.t - 1e-3) ++r;
    if (r == reference.size() || std::abs(reference[r].t - p.t) > 1e-3) continue;
    const double d = std::hypot(p.pose.x - reference[r].pose.x, p.pose.y - reference[r].pose.y);
    squares += d * d;
    e.max = std::max(e.max, d);
    headings += std::abs(core::wrap_angle(p.pose.theta - reference[r].pose.theta));
    ++e.matched;
  }
  if (e.matched == 0) core::fail<std::invalid_argument>("no pose has a reference at the same time");
  e.rmse = std::sqrt(squares / static_cast<double>(e.matched));
  e.mean_heading = headings / static_cast<double>(e.matched);
  return e;
}

std::vector<TimedPose> scan_poses(const core::Log& log) {
  std::vector<TimedPose> out;
  for (const core::Scan& s : log.scans) out.push_back({s.t, s.robot});
  return out;
}

}  // namespace intgrid::slam
