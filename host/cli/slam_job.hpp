// The `slam` job: a log through one of two SLAM engines, the submap SLAM with loop closure
// (slam::run_submap_slam, the default) or the thesis's event-driven grid SLAM
// (slam::run_grid_slam), written as a trajectory, a ROS map, a PNG with the trajectory drawn and
// the run's metrics; scored against a reference log (ATE) and against the Freiburg benchmark's
// relations.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/memory_budget.hpp"
#include "cli/options.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/relations.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {

// `--engine submaps|grid`.
enum class SlamEngine { submaps, grid };

// "submaps", "grid": the engine's name, as --engine and metrics.json spell it.
const char* engine_name(SlamEngine engine);

struct SlamJobOptions {
  std::filesystem::path log;
  std::filesystem::path out;
  std::optional<std::filesystem::path> reference;
  std::optional<std::filesystem::path> relations;  // a benchmark relations file to score against
  std::optional<std::filesystem::path> tum;        // also write the trajectory here, TUM format
  core::Arithmetic arithmetic = core::Arithmetic::integer;
  SlamEngine engine = SlamEngine::submaps;
  slam::SubmapSlamConfig submap_config;  // the settings of --engine submaps
  slam::GridSlamConfig grid_config;      // the settings of --engine grid
  bool progress = true;
  double max_memory_bytes = default_memory_limit_bytes();  // --max-memory
};

struct SlamJobResult {
  SlamEngine engine = SlamEngine::submaps;
  slam::SlamRun run;
  std::optional<slam::SubmapSlamStats> submap_stats;  // the submaps engine's counts
  double seconds = 0.0;                               // the SLAM alone, without reading or writing
  double log_seconds = 0.0;                           // time the log spans
  std::optional<slam::TrajectoryError> ate;
  std::optional<slam::TrajectoryError> odometry_ate;  // the raw odometry against the same reference
  std::optional<slam::RelationError> relations;       // the SLAM trajectory against the relations
  std::optional<slam::RelationError> odometry_relations;  // the raw odometry against them
  nlohmann::json metrics;                                 // what metrics.json holds
};

// Checks the chosen engine's settings (OptionError naming the flag), reads the log (and
// reference, and relations), runs SLAM, writes DIR/trajectory.txt, map.yaml +
// map.pgm, map.png and metrics.json (and the TUM trajectory), each atomically. A relations file
// none of whose relations matches the log's scans (within slam::kRelationTolerance) is an
// InputError naming its first relation's line and t1, found before SLAM runs.
SlamJobResult run_slam_job(const SlamJobOptions& options);

// SubmapSlamConfig's fields as check_submap_slam_config names them -> the flags of `slam`.
const FieldFlags& submap_slam_flags();
// Throws OptionError naming the flag for a submaps setting check_submap_slam_config refuses.
void check_submap_slam_options(const slam::SubmapSlamConfig& config);

// The run in one line for people, without the output's path: for the submaps engine "ATE A m
// (raw odometry B m), N nodes in S submaps, C loop closures of L searched, T s for D s of data
// (Fx real time)"; for the grid engine E(sigma) in place of the nodes and loop closures; the ATE
// only with a reference.
std::string slam_summary(const SlamJobResult& result);

// One line for people: "relations: 2984 matched, 0 unmatched; translation 0.0523 ± 0.0311 m,
// rotation 0.914 ± 1.2 deg", with what in front of the colon.
std::string relation_summary(const std::string& what, const slam::RelationError& e);

}  // namespace intgrid::cli
