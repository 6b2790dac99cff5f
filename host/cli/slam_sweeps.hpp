// `intgrid figure slam-sweeps`: the thesis's SLAM experiments (section 3.6) on a simulated office
// floor with 10 cm cells: E(sigma), E(d), trajectory error and run time against lambda (scans
// between localizations), xi (scans between mappings) and the pose grid's size, in integer and
// double arithmetic. CSVs, gnuplot plots and the built maps.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "intgrid/slam/grid_slam_engine.hpp"

namespace intgrid::cli {

inline constexpr std::size_t kSlamSweepScans = 1170;     // the default --scans: three laps
inline constexpr std::size_t kSlamSweepQuickScans = 24;  // --quick
inline constexpr std::size_t kSlamSweepDepthScans =
    390;  // scans of each pose-grid size run: one lap

// The SLAM settings of the sweeps: GridSlamConfig's with 10 cm cells and 256 headings a turn, a
// heading step of 1.4 degrees that moves a point 4 m away by one cell, the thesis's unpruned
// pose grid and tempering 3.
slam::GridSlamConfig default_sweep_config();

struct SlamSweepOptions {
  std::filesystem::path out;
  std::uint64_t seed = 1;
  std::size_t scans = 0;  // 0: kSlamSweepScans, or kSlamSweepQuickScans with quick
  bool quick = false;     // fewer scans and sweep points (tests)
  std::string gnuplot = "gnuplot";
  // Every run's settings but lambda, xi and the window, which the sweeps vary (lambda is the xi
  // sweep's, xi the lambda sweep's, the window both's).
  slam::GridSlamConfig config = default_sweep_config();
};

// Runs the sweeps and writes DIR/slam_lambda.csv, slam_xi.csv, slam_depth.csv, slam_world.png,
// slam_maps.png and, when gnuplot runs, slam_lambda.png, slam_xi.png, slam_depth.png (each
// atomically); prints progress on a terminal, a summary table, and a note if gnuplot is missing.
void run_slam_sweeps(const SlamSweepOptions& options);

// Adds `slam-sweeps` to the `figure` command.
void add_slam_sweeps_figure(CLI::App& figure);

}  // namespace intgrid::cli
