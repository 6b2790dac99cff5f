// The `slam` job: a log through the event-driven grid SLAM, written as a trajectory, a ROS map,
// a PNG with the trajectory drawn and the run's metrics.
#pragma once

#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "golden/slam_run.hpp"
#include "golden/trajectory_metrics.hpp"

namespace intgrid {

struct SlamJobOptions {
  std::filesystem::path log;
  std::filesystem::path out;
  std::optional<std::filesystem::path> reference;
  Arithmetic arithmetic = Arithmetic::integer;
  SlamConfig config;
  bool progress = true;
};

struct SlamJobResult {
  SlamRun run;
  double seconds = 0.0;      // the SLAM alone, without reading or writing
  double log_seconds = 0.0;  // time the log spans
  std::optional<TrajectoryError> ate;
  std::optional<TrajectoryError> odometry_ate;  // the raw odometry against the same reference
  nlohmann::json metrics;                       // what metrics.json holds
};

// Reads the log (and reference), runs SLAM, writes DIR/trajectory.txt, map.yaml + map.pgm,
// map.png and metrics.json, each atomically.
SlamJobResult run_slam_job(const SlamJobOptions& options);

}  // namespace intgrid
