// A SLAM run over a sensor log: the log's doubles turned into the per-scan path's integers,
// each scan processed, the estimates turned back into world poses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/trajectory.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"

namespace intgrid::slam {

using core::TimedPose;

struct SlamRun {
  std::vector<TimedPose> trajectory;  // one per scan, in the log's frame
  std::vector<double> sigma;          // positional standard deviation per scan (m)
  core::Grid<std::int8_t> map;        // S_eps indices, in the log's frame
  core::SepsCodec codec{8, 0.1};
  core::Pose2 frame;  // the SLAM frame (the first scan's robot pose) in the log's frame
  std::size_t scans = 0;
  std::size_t localizations = 0;
  std::size_t mappings = 0;
  std::size_t skipped_scans = 0;  // no usable reading: only the motion update ran
  std::size_t readings = 0;
  std::size_t unusable_readings = 0;  // zero, NaN, negative, at or past max range
  double mean_sigma() const;          // E(sigma)
};

// The per-scan path's inputs of every scan of the log: ranges in millimetres, odometry
// increments from the previous scan's robot pose. Counts readings into run.
std::vector<QuantizedScan> quantize_scans(const core::Log& log, const GridSlamConfig& config,
                                          SlamRun& run);

// Throws std::invalid_argument with a clear message for a log SLAM cannot use: no scans, no
// odometry (no ODOM record and every scan at the same pose), a first scan without ranges.
void check_slam_log(const core::Log& log);

// Throws std::invalid_argument naming the first scan whose geometry (beam count, bearings, range
// limit or sensor mount) differs from the first scan's: the grid engine (run_grid_slam, GridSlam)
// sets its pose grid up for one geometry. SubmapSlam takes each scan's own.
void check_one_sensor_geometry(const core::Log& log);

// The farthest any scan's robot pose lies from the first scan's (m), 0 without scans: the reach
// run_grid_slam sizes its map for (GridSlam's reach_m).
double odometry_reach(std::span<const core::Scan> scans);

// Runs the whole log. progress(done, total) after each scan.
SlamRun run_grid_slam(const core::Log& log, const GridSlamConfig& config,
                      core::Arithmetic arithmetic, const core::Progress& progress = {});

// The map's probabilities on an axis-aligned grid of the log's frame (nearest cell): the part any
// scan reached and 10 cells around it. `frame` is the SLAM frame in the log's frame.
core::ProbabilityGrid slam_map_probabilities(const core::Grid<std::int8_t>& map,
                                             const core::SepsCodec& codec,
                                             const core::Pose2& frame);
core::ProbabilityGrid slam_map_probabilities(const SlamRun& run);

}  // namespace intgrid::slam
