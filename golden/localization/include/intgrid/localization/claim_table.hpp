// One reading's claims on the cells of one step (rules 1 and 2, docs/algorithms.md 7): what the
// pose lattice's directions and the refinement on the map's own cells both read.
#pragma once

#include <cstddef>
#include <vector>

namespace intgrid::localization {

template <class Score>
struct ClaimTable {
  // claim[rho] for a first hit rho steps away: claim[0] = 0 (never a first hit), then the narrow
  // ISM of z on cells of `step` with sigma_eff, past z plus 8 sigma_eff, cut after its last
  // non-zero claim or at longest + 1, and one final 0 that every longer distance reads.
  std::vector<Score> claim;
  Score top = 0;  // the strongest claim (0 if none is positive)
};

// Integer Score: each claim is the nearest step of the reading's own S_eps scale, lambda =
// max(logit(Pmax), 1e-9) / seps_levels, clamped to [-min(top, veto_levels), top]. Double Score:
// the log-odds those indices round (n lambda before rounding), bounded alike. Requires z and
// sigma_eff finite and positive, step positive, seps_levels >= 1, 0 <= veto_levels.
template <class Score>
ClaimTable<Score> claim_table(double z, double sigma_eff, double step, int seps_levels,
                              int veto_levels, std::size_t longest);

}  // namespace intgrid::localization
