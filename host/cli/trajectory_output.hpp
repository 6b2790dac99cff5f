// What the jobs that estimate a trajectory (`slam`, `localize`) write and report alike: the
// trajectory file, the ATE and the relation errors in metrics.json and relations.csv, the
// positions drawn on a map, the process's peak memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/slam/relations.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {

// {"rmse_m", "max_m", "matched", "mean_heading_error_deg"}.
nlohmann::json error_json(const slam::TrajectoryError& e);

// "t x y theta" lines (s, m, m, rad) under a header line naming `what` the poses are, atomically.
void write_trajectory(const std::filesystem::path& file, const std::vector<slam::TimedPose>& poses,
                      const std::string& what);

std::vector<core::Pose2> positions(const std::vector<slam::TimedPose>& poses);

// The scale line of a map.png caption: one pixel a cell of `map`, north up, in `frame` ("the
// log's", "the map's").
std::string map_scale_caption(const core::GridGeometry& map, const std::string& frame);

// The peak resident set of this process so far (bytes; Linux reports ru_maxrss in KiB).
std::size_t peak_memory_bytes();

// A benchmark relations file and the log's raw odometry scored on it (relations are relative:
// the odometry's frame does not matter). A file none of whose relations matches a scan of the
// log is an InputError naming the file's first relation.
struct RelationScoring {
  std::vector<slam::Relation> relations;
  std::vector<slam::RelationResult> odometry;
};
RelationScoring read_relations_for(const std::filesystem::path& relations_file,
                                   const std::filesystem::path& log_file, const core::Log& log);

// metrics.json's relation entries: the file's path, the estimate's and the raw odometry's
// summaries (as the job computed them), the estimate's worst stretches among its results (times
// also from t0, the log's first scan).
void add_relation_metrics(nlohmann::json& metrics, const std::filesystem::path& file,
                          const slam::RelationError& summary,
                          const slam::RelationError& odometry_summary,
                          std::span<const slam::RelationResult> results, double t0);

// DIR/relations.csv: each relation with the estimate's error and the raw odometry's (empty where
// a relation matched no pose), in the relations file's order.
void write_relation_errors(const std::filesystem::path& file,
                           std::span<const slam::RelationResult> results,
                           std::span<const slam::RelationResult> odometry_results);

// The poses in time order (score_relations needs it; a log's scans normally are).
std::vector<slam::TimedPose> by_time(std::vector<slam::TimedPose> poses);

}  // namespace intgrid::cli
