// `intgrid figure globloc-sweeps`: the global localization experiments of thesis section 4.5 on a
// known map with simulated readings (the map used as the world): success rate, mean position and
// heading errors of every method (pose occupancy grid, Markov with the Gaussian and the mixture
// beam models, likelihood field) against the number of readings, the sensor noise, uniform
// contamination, small unmodelled obstacles and the distance to one large unmodelled obstacle.
// One CSV and one gnuplot plot per sweep, and a table.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "intgrid/experiments/global_localization_trials.hpp"
#include "intgrid/localization/global_localization.hpp"

namespace intgrid::cli {

struct GlobLocSweepOptions {
  std::filesystem::path map;
  std::filesystem::path out = "globloc-sweeps";
  std::size_t trials = 50;  // random true poses per sweep point
  std::uint64_t seed = 1;
  unsigned threads = 0;           // 0: std::thread::hardware_concurrency()
  bool quick = false;             // two points a sweep (tests)
  std::vector<std::string> only;  // the sweeps to run, by name (empty: all five)
  std::string gnuplot = "gnuplot";
  double clearance = 0.3;  // m from a true position to the map's nearest non-free cell
  localization::GlobalLocConfig
      config;                // the localizers' settings, one LocalizationMap for every trial
  bool fixed_sigma = false;  // false: in the noise sweep the localizers' sigma is the noise
  // The default condition; each sweep varies one of its fields.
  experiments::GlobalTrialConditions conditions;
};

// Runs every trial (every method on the same readings) on a pool of threads, writes
// DIR/globloc_{readings,noise,contamination,obstacles,large_obstacle}.csv, globloc_timing.csv and,
// when gnuplot runs, one PNG per sweep (each atomically); prints progress on a terminal and the
// tables. The CSVs of the sweeps are the same for any thread count.
void run_globloc_sweeps(const GlobLocSweepOptions& options);

// Adds `globloc-sweeps` to the `figure` command.
void add_globloc_sweeps_figure(CLI::App& figure);

}  // namespace intgrid::cli
