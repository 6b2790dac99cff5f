// The `localize` job: a log's scans localized one after another in a known map
// (navigation::KnownMapLocalizer): from a given pose at the first scan, or found by global
// localization; lost when the scans stop fitting the map, and found again. Written as a
// trajectory, each scan's state and fit, the path drawn on the map and the run's metrics; scored
// against a reference log (ATE, no alignment: the reference must be in the map's frame).
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "intgrid/core/types.hpp"
#include "intgrid/navigation/known_map_localizer.hpp"
#include "intgrid/slam/relations.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {

struct LocalizeJobOptions {
  std::filesystem::path map;  // ROS map_server YAML
  std::filesystem::path log;
  std::filesystem::path out;
  std::optional<core::Pose2> initial;  // the robot's pose in the map's frame at the first scan
  std::optional<std::filesystem::path> reference;
  std::optional<std::filesystem::path> relations;  // benchmark relations of the log
  std::optional<std::filesystem::path> tum;        // also write the tracked scans here, TUM format
  core::Arithmetic arithmetic = core::Arithmetic::integer;
  navigation::KnownMapLocalizerConfig config;  // its tracking cell is the map's
  bool progress = true;
};

struct LocalizeJobResult {
  std::vector<slam::TimedPose> trajectory;       // the scans with a pose (tracking)
  std::vector<navigation::LocalizerStep> steps;  // every scan's
  double seconds = 0.0;  // the localization alone, without reading or writing
  std::optional<slam::TrajectoryError> ate, odometry_ate;
  std::optional<slam::RelationError> relations, odometry_relations;
  nlohmann::json metrics;  // what metrics.json holds
};

// Reads the map and the log (and reference, relations), localizes every scan, writes
// DIR/trajectory.txt (the tracked scans), fit.csv (t, state, evidence, matched, wide, hits, fit,
// fused scans), map.png, metrics.json and with relations relations.csv, each atomically. A map
// whose cell the SLAM's settings refuse is an InputError naming the map's resolution.
LocalizeJobResult run_localize_job(const LocalizeJobOptions& options);

}  // namespace intgrid::cli
