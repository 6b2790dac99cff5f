#include "intgrid/core/narrow_ism.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

void narrow_ism(const GaussianBeamModel& model, double z, double cell, std::span<double> out) {
  const std::size_t n = out.size();
  // Pass 1: log of each term p(z|d_k) / 2^(k - k_z), and the largest of them.
  // Counting the 2^-k from the cell nearest z keeps the exponents of the terms
  // that matter small, and fma gives z - d_k with one rounding: both keep a
  // million-cell line of sight as precise as a short one.
  const double k_z = std::clamp(std::round(z / cell), 1.0, static_cast<double>(n));
  double log_max = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k <= n; ++k) {
    const double kd = static_cast<double>(k);
    const double term = model.log_density_of_error(std::fma(-kd, cell, z), kd * cell) -
                        (kd - k_z) * std::numbers::ln2;
    out[k - 1] = term;
    log_max = std::max(log_max, term);
  }
  if (!std::isfinite(log_max))
    fail<std::invalid_argument>("sigma " + number_text(model.sigma0) +
                                " m is too narrow for a reading at " + number_text(z) +
                                " m: every cell's likelihood underflows");
  // Pass 2: terms rescaled by the largest, so the denominator is at least 1.
  double denominator = 0.0;
  for (double& term : out) {
    term = std::exp(term - log_max);
    denominator += term;
  }
  // Pass 3: eq. 2.12 as a prefix sum: numerator_i = (1/2) sum_{k<i} w_k + w_i.
  double prefix = 0.0;
  for (double& term : out) {
    const double w = term;
    term = (0.5 * prefix + w) / denominator;
    prefix += w;
  }
}

std::vector<double> narrow_ism(const GaussianBeamModel& model, double z, double cell,
                               std::size_t cells) {
  std::vector<double> out(cells);
  narrow_ism(model, z, cell, out);
  return out;
}

std::size_t predicted_argmax_cell(const GaussianBeamModel& model, double z, double cell,
                                  std::size_t cells) {
  const double m = std::floor(z / cell);
  if (m < 1.0) return 1;
  if (m >= static_cast<double>(cells)) return cells;
  const double p_m = model.log_density(z, m * cell);
  const double p_next = model.log_density(z, (m + 1.0) * cell);
  return static_cast<std::size_t>(m) + (p_m > p_next ? 0 : 1);
}

}  // namespace intgrid::core
