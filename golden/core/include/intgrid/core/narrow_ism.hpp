// The exact Bayesian inverse sensor model of a narrow-FOV nearest-target sensor
// (thesis eq. 2.12), in linear time and stable for any number of cells.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "intgrid/core/sensor_model.hpp"

namespace intgrid::core {

// P(o_k | z) for the line-of-sight cells k = 1..out.size(), cell k at distance
// d_k = k * cell, every prior 1/2. Works in the log domain, rescaled by the
// dominant term, so 2^-k and far Gaussian tails never underflow the answer.
// Requires cell > 0, out non-empty and z finite.
void narrow_ism(const GaussianBeamModel& model, double z, double cell, std::span<double> out);
std::vector<double> narrow_ism(const GaussianBeamModel& model, double z, double cell,
                               std::size_t cells);

// The 1-based cell holding the ISM's maximum by Theorem 1 (eq. 2.20): floor(z/s)
// if p(z|d_m) > p(z|d_{m+1}), else floor(z/s) + 1; clamped to 1..cells.
std::size_t predicted_argmax_cell(const GaussianBeamModel& model, double z, double cell,
                                  std::size_t cells);

// Brute-force Bayes over all 2^n configurations of n <= 24 cells with prior 1/2:
// returns P(o_i | z) for each cell i, given the likelihood p(z | g) of every
// configuration g (bit i set = cell i occupied). The independent oracle for every ISM.
template <class Likelihood>
std::vector<double> brute_force_ism(std::size_t n, Likelihood&& likelihood) {
  std::vector<long double> occupied(n, 0.0L);
  long double total = 0.0L;
  const std::size_t configurations = std::size_t{1} << n;
  for (std::size_t g = 0; g < configurations; ++g) {
    const long double p = likelihood(g);
    total += p;
    for (std::size_t i = 0; i < n; ++i)
      if (g >> i & 1u) occupied[i] += p;
  }
  std::vector<double> result(n);
  for (std::size_t i = 0; i < n; ++i) result[i] = static_cast<double>(occupied[i] / total);
  return result;
}

// The narrow-FOV configuration likelihood of eq. 2.7-2.10: p(z | nearest occupied
// cell of g), nothing for the all-empty configuration.
inline long double narrow_configuration_likelihood(const GaussianBeamModel& model, double z,
                                                   double cell, std::size_t g) {
  if (g == 0) return 0.0L;
  const std::size_t nearest = static_cast<std::size_t>(__builtin_ctzll(g)) + 1;
  return static_cast<long double>(model.density(z, static_cast<double>(nearest) * cell));
}

}  // namespace intgrid::core
