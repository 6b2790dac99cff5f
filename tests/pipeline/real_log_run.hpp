// The grid SLAM on the bundled real log (data/README.md), for the data and long tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "data_dir.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::slam::test {

struct Scored {
  SlamRun run;
  TrajectoryError ate, odometry;
};

// The grid SLAM on the first `scans` scans of the bundled real log (all of them by default),
// scored against the reference trajectory (data/README.md) with the raw odometry beside it.
inline Scored run_real_log(core::Arithmetic arithmetic,
                           std::size_t scans = std::numeric_limits<std::size_t>::max()) {
  const std::string data = intgrid::test::data_dir();
  core::Log log = io::read_log(data + "/malaga_telecom_loop.log");
  log.scans.resize(std::min(log.scans.size(), scans));
  const std::vector<TimedPose> reference =
      scan_poses(io::read_log(data + "/malaga_telecom_loop_reference.log"));
  Scored s{run_grid_slam(log, GridSlamConfig{}, arithmetic), {}, {}};
  s.ate = absolute_trajectory_error(s.run.trajectory, reference);
  s.odometry = absolute_trajectory_error(scan_poses(log), reference);
  return s;
}

}  // namespace intgrid::slam::test
