// The `localize` job: a log's scans tracked one after another in a known map
// (slam::MapLocalizer) from a given pose at the first scan, written as a trajectory, each scan's
// fit, the path drawn on the map and the run's metrics; scored against a reference log (ATE, no
// alignment: the reference must be in the map's frame).
#pragma once

#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "intgrid/core/types.hpp"
#include "intgrid/slam/map_localizer.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {

struct LocalizeJobOptions {
  std::filesystem::path map;  // ROS map_server YAML
  std::filesystem::path log;
  std::filesystem::path out;
  core::Pose2 initial;  // the robot's pose in the map's frame at the first scan
  std::optional<std::filesystem::path> reference;
  core::Arithmetic arithmetic = core::Arithmetic::integer;
  slam::SubmapSlamConfig config;  // its cell is the map's
  bool progress = true;
};

struct LocalizeJobResult {
  std::vector<slam::TimedPose> trajectory;
  std::vector<slam::MapFix> fixes;
  double seconds = 0.0;  // the localization alone, without reading or writing
  std::optional<slam::TrajectoryError> ate, odometry_ate;
  nlohmann::json metrics;  // what metrics.json holds
};

// Reads the map and the log (and reference), localizes every scan, writes DIR/trajectory.txt,
// fit.csv (t, evidence, matched, wide), map.png and metrics.json, each atomically. A map whose
// cell the SLAM's settings refuse is an InputError naming the map's resolution.
LocalizeJobResult run_localize_job(const LocalizeJobOptions& options);

}  // namespace intgrid::cli
