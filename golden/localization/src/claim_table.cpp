#include "intgrid/localization/claim_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"

namespace intgrid::localization {
namespace {
// The ISM's window past z: beyond z + 8 sigma it is 1/2 to 1e-14 (ism_cells_for_reading).
constexpr double kIsmWindowSigmas = 8.0;
// Past some 15 m with 64 headings Pmax is 1/2 to within rounding (1e-14): this floor on lambda
// rounds such a reading's positive claims to 0, so by rule 2 it claims nothing, instead of
// amplifying rounding noise to seps_levels.
constexpr double kLeastLogOdds = 1e-9;
}  // namespace

template <class Score>
ClaimTable<Score> claim_table(double z, double sigma_eff, double step, int seps_levels,
                              int veto_levels, std::size_t longest) {
  const core::GaussianBeamModel model{sigma_eff, 0.0};
  const auto cells =
      static_cast<std::size_t>(std::ceil((z + kIsmWindowSigmas * sigma_eff) / step)) + 1;
  std::vector<double> ism(cells);
  core::narrow_ism(model, z, step, ism);
  ClaimTable<Score> out;
  out.claim.assign(cells + 1, 0);
  // The reading's own S_eps step: its strongest claim is seps_levels however broad its ISM. A
  // reading whose ISM is broad (far, so sigma_eff is wide) still says where the robot cannot be
  // and where it may be, and counts as much as a near one.
  const double lambda =
      std::max(core::logit(*std::max_element(ism.begin(), ism.end())), kLeastLogOdds) / seps_levels;
  for (std::size_t k = 1; k <= cells; ++k) {
    const double n =
        std::clamp(core::logit(ism[k - 1]) / lambda, -double(seps_levels), double(seps_levels));
    if constexpr (std::is_integral_v<Score>)
      out.claim[k] = static_cast<Score>(std::lround(n));
    else
      out.claim[k] = n * lambda;
    out.top = std::max(out.top, out.claim[k]);
  }
  const Score veto_bound =
      std::is_integral_v<Score> ? Score(veto_levels) : Score(veto_levels * lambda);
  const Score veto = std::min(out.top, veto_bound);
  for (Score& n : out.claim) n = std::clamp(n, -veto, out.top);  // rule 2, tightened
  std::size_t size = std::min(out.claim.size(), longest + 1);
  while (size > 1 && out.claim[size - 1] == 0) --size;
  out.claim.resize(size);
  out.claim.push_back(0);
  return out;
}

template ClaimTable<std::int32_t> claim_table<std::int32_t>(double, double, double, int, int,
                                                            std::size_t);
template ClaimTable<double> claim_table<double>(double, double, double, int, int, std::size_t);

}  // namespace intgrid::localization
