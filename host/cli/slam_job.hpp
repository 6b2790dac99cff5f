// The `slam` job: a log through the event-driven grid SLAM, written as a trajectory, a ROS map,
// a PNG with the trajectory drawn and the run's metrics.
#pragma once

#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {

struct SlamJobOptions {
  std::filesystem::path log;
  std::filesystem::path out;
  std::optional<std::filesystem::path> reference;
  core::Arithmetic arithmetic = core::Arithmetic::integer;
  slam::SlamConfig config;
  bool progress = true;
};

struct SlamJobResult {
  slam::SlamRun run;
  double seconds = 0.0;      // the SLAM alone, without reading or writing
  double log_seconds = 0.0;  // time the log spans
  std::optional<slam::TrajectoryError> ate;
  std::optional<slam::TrajectoryError> odometry_ate;  // the raw odometry against the same reference
  nlohmann::json metrics;                             // what metrics.json holds
};

// Reads the log (and reference), runs SLAM, writes DIR/trajectory.txt, map.yaml + map.pgm,
// map.png and metrics.json, each atomically.
SlamJobResult run_slam_job(const SlamJobOptions& options);

}  // namespace intgrid::cli
