// Markov localization on a map's candidates: the baselines of global localization.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "intgrid/localization/global_loc_config.hpp"
#include "intgrid/localization/localization_map.hpp"
#include "intgrid/localization/range_reading.hpp"

namespace intgrid::localization {

// Markov localization over the candidates of a map, the baselines (markov, markov_mixture,
// likelihood_field) in double as a user would write them: each reading multiplies every
// candidate's belief by p(z | x), one exp per candidate, and normalizes (bel <- eta p(z|x) bel).
// Beam models read the expected range from the map's first-hit table: first_hit_steps *
// step_length capped at max_range, max_range with no hit.
//   markov:           p = N(z; expected, sigma_eff)
//   markov_mixture:   p = z_hit N(z; expected, sigma_eff) + z_short lambda e^(-lambda z) /
//                     (1 - e^(-lambda expected)) below expected + z_rand / max_range (+ z_max at
//                     max_range, which a usable reading never is); the Gaussian is not truncated
//                     to [0, max_range] (as in ROS AMCL)
//   likelihood_field: p = z_hit N(d; sigma_eff) + z_rand / max_range, d the distance of the
//                     reading's endpoint (from the pose cell's centre along heading + bearing, not
//                     binned) to the nearest occupied map cell, no hit term outside the map
// N is the normalized Gaussian density and sigma_eff the pose grid's (rule 1).
class MarkovLocalization {
 public:
  // Uniform prior over the candidates. Throws std::invalid_argument for pose_grid, and (naming
  // memory_limit) when the two beliefs beside the map's tables would exceed the configuration's
  // memory limit.
  MarkovLocalization(const LocalizationMap& map, GlobalMethod method);

  // Fuses one reading. Returns false, leaving the belief unchanged, when every candidate's
  // product is 0 in double (the textbook's eta is then undefined). Throws std::invalid_argument
  // for a range that is not finite and positive or not below max_range, or a bearing that is not
  // finite.
  bool update(const RangeReading& reading);
  // candidate_cells() elements in the candidate layout (k * candidates + c), summing to 1.
  std::span<const double> belief() const { return belief_; }
  std::size_t dropped() const { return dropped_; }

 private:
  const LocalizationMap* map_;
  GlobalMethod method_;
  std::vector<double> belief_, next_;
  std::size_t dropped_ = 0;
};

}  // namespace intgrid::localization
