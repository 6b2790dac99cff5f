// The submap SLAM on a run of consecutive scans of a Freiburg benchmark log, in both arithmetics,
// scored with the benchmark's relations that fall inside them. The logs are not bundled: tests
// skip, saying so, where ../shared/data/benchmark (or INTGRID_BENCHMARK_DIR) does not hold them.
#pragma once

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "intgrid/io/log_io.hpp"
#include "intgrid/io/relations_io.hpp"
#include "intgrid/slam/relations.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"
#include "test_support.hpp"

namespace intgrid::slam::test {

struct Segment {
  RelationError slam_int, slam_double, odometry;
  SubmapSlamStats stats_int, stats_double;
  double map_cells_int = 0.0, map_cells_double = 0.0;  // of the map each run returned
};

// Scans [first, first + scans) of NAME.clf in both arithmetics, and their raw odometry.
inline Segment run_segment(const std::string& name, std::size_t first, std::size_t scans) {
  const auto dir = intgrid::test::benchmark_dir();
  core::Log log = io::read_log(dir / (name + ".clf"));
  first = std::min(first, log.scans.size());
  log.scans.erase(log.scans.begin(), log.scans.begin() + static_cast<std::ptrdiff_t>(first));
  log.scans.resize(std::min(log.scans.size(), scans));
  const std::vector<Relation> relations =
      io::relations_of(io::read_relations(dir / (name + ".relations")));
  Segment s;
  s.odometry = score_relations(scan_poses(log), relations);
  const SlamRun integer =
      run_submap_slam(log, SubmapSlamConfig{}, core::Arithmetic::integer, &s.stats_int);
  s.slam_int = score_relations(integer.trajectory, relations);
  s.map_cells_int = static_cast<double>(integer.map.cells.size());
  const SlamRun floating =
      run_submap_slam(log, SubmapSlamConfig{}, core::Arithmetic::floating, &s.stats_double);
  s.slam_double = score_relations(floating.trajectory, relations);
  s.map_cells_double = static_cast<double>(floating.map.cells.size());
  // The figures docs/results.md quotes for the segments.
  std::printf(
      "%s, scans %zu to %zu: odometry %.3f m %.2f deg, integer %.3f m %.2f deg, double %.3f m %.2f "
      "deg (%zu relations); submaps %zu/%zu, loop closures %zu/%zu, optimizations %zu/%zu "
      "(integer/double)\n",
      name.c_str(), first, first + log.scans.size() - 1, s.odometry.trans_mean,
      s.odometry.rot_mean_deg, s.slam_int.trans_mean, s.slam_int.rot_mean_deg,
      s.slam_double.trans_mean, s.slam_double.rot_mean_deg, s.odometry.matched, s.stats_int.submaps,
      s.stats_double.submaps, s.stats_int.loop_closures, s.stats_double.loop_closures,
      s.stats_int.optimizations, s.stats_double.optimizations);
  return s;
}

inline bool present(const std::string& name) {
  const auto dir = intgrid::test::benchmark_dir();
  return std::filesystem::exists(dir / (name + ".clf")) &&
         std::filesystem::exists(dir / (name + ".relations"));
}

}  // namespace intgrid::slam::test
