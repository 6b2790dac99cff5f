// Sensor models p(z | d): the density of a reading z when the nearest obstacle
// on the line of sight is at distance d (thesis 2.2, eq. 2.11).
#pragma once

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace intgrid {

// Gaussian narrow-FOV model whose standard deviation may grow with distance:
// sigma(d) = sigma0 * (1 + k_d * d). Always the normalized density, because the
// normalization cancels in the ISM only while sigma is the same for every term.
struct GaussianBeamModel {
  double sigma0 = 0.03;  // metres
  double k_d = 0.0;      // relative growth of sigma per metre of distance

  double sigma(double d) const { return sigma0 * (1.0 + k_d * d); }
  double log_density(double z, double d) const { return log_density_of_error(z - d, d); }
  // The same, given the error z - d directly: callers that can compute it more
  // precisely than by subtracting two large numbers pass it here.
  double log_density_of_error(double error, double d) const {
    const double s = sigma(d);
    const double u = error / s;
    return -0.5 * u * u - std::log(s) - 0.5 * std::log(2.0 * std::numbers::pi);
  }
  double density(double z, double d) const { return std::exp(log_density(z, d)); }
};

// Throws std::invalid_argument naming the offending parameter.
inline void check_model(const GaussianBeamModel& m) {
  if (!(m.sigma0 > 0.0) || !std::isfinite(m.sigma0))
    throw std::invalid_argument("sigma must be a positive finite number");
  if (!(m.k_d >= 0.0) || !std::isfinite(m.k_d))
    throw std::invalid_argument("k_d must be a non-negative finite number");
}

}  // namespace intgrid
