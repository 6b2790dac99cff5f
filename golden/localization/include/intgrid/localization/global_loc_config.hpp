// The settings of global localization with pose occupancy grids (docs/algorithms.md 7), and the
// methods a user may pick.
#pragma once

#include <cstddef>
#include <cstdint>

#include "intgrid/core/range_sensor.hpp"

namespace intgrid::localization {

enum class GlobalMethod {
  pose_grid,         // the pose occupancy grid: S_eps index sums, integer only per reading
  markov,            // Markov localization, Gaussian beam model, double
  markov_mixture,    // Markov localization, hit + short + random + max mixture, double
  likelihood_field,  // Markov localization, likelihood field (ROS AMCL's default), double
};

struct GlobalLocConfig {
  double pose_res = 0.2;                 // pose-grid step (m); not finer than the map's resolution
  int headings = 64;                     // heading bins, also the rays' direction bins
  core::RangeSensor sensor{0.03, 30.0};  // the readings' noise and range
  int seps_bits = 8;                     // per-reading index width
  // Each reading's claims are quantized with its own eps, such that its strongest claim is this
  // index: with one eps for all, a far reading (sigma_eff grows with the heading step times z)
  // claims 0 to 2 against a near one's 16, and a pose near any wall outscores the true one.
  int seps_levels = 16;
  // A reading's negative claims are bounded by this (rule 2 bounds them by its strongest claim):
  // a reading cut short or contaminated that runs past the true pose's first hit would otherwise
  // veto the true pose with the weight of a match.
  int veto_levels = 8;
  // Baselines' beam-model weights (Probabilistic Robotics 6.3; AMCL's defaults).
  // z_hit and lambda_short must be positive, the others non-negative.
  double z_hit = 0.95, z_short = 0.1, z_max = 0.05, z_rand = 0.05, lambda_short = 0.1;
  // The most a map's tables and one localization's scores may take (bytes): a LocalizationMap or
  // MarkovLocalization that would need more is refused before it allocates.
  std::size_t memory_limit = 1'000'000'000;
  // Levels of the pose grid's refinement on the map's own cells, each halving the position and
  // heading steps (0: none, the hypotheses stay on the pose lattice). Its finest heading bin is
  // 2 pi / (headings 2^refine_levels).
  int refine_levels = 4;
  // The refinement reads a reading whose first hit lies before its range, while its ray runs
  // along a wall from there to its endpoint, as a hit at its range: a wall met at a grazing angle
  // is entered up to cell / sin(angle) before its surface where the map's wall is ragged, and its
  // early first hit would veto the true pose. Off by default: measured on the benchmark logs
  // only, not yet on the sweeps the defaults are reported on (docs/results.md).
  bool grazing_hits = false;
};

// Throws std::invalid_argument naming the offending field.
void check_global_loc_config(const GlobalLocConfig& config);

}  // namespace intgrid::localization
