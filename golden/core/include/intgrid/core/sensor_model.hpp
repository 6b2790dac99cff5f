// Sensor models p(z | d): the density of a reading z when the nearest obstacle
// on the line of sight is at distance d (thesis 2.2, eq. 2.11).
#pragma once

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

// log of the normalized Gaussian density of an error, for standard deviation sigma.
inline double gaussian_log_density(double error, double sigma) {
  const double u = error / sigma;
  return -0.5 * u * u - std::log(sigma) - 0.5 * std::log(2.0 * std::numbers::pi);
}

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
    return gaussian_log_density(error, sigma(d));
  }
  double density(double z, double d) const { return std::exp(log_density(z, d)); }
};

// Throws std::invalid_argument naming the offending parameter.
inline void check_model(const GaussianBeamModel& m) {
  if (!(m.sigma0 > 0.0) || !std::isfinite(m.sigma0))
    fail<std::invalid_argument>("sigma must be a positive finite number");
  if (!(m.k_d >= 0.0) || !std::isfinite(m.k_d))
    fail<std::invalid_argument>("k_d must be a non-negative finite number");
}

// Large-FOV nearest-target model (thesis figure 2.7, docs/algorithms.md 3): a normalized
// Gaussian of the reading around the distance d of the nearest occupied ring, wider for
// farther, more off-axis and smaller obstacles:
//   sigma = sigma0 (1 + k_d d) (1 + k_theta theta) (1 + k_size / size) / (1 + k_size),
// theta in [0, 1] the off-axis angle of the occupied sector nearest the axis over FOV/2,
// size the number of occupied sectors in that ring.
struct ConeSensorModel {
  double sigma0 = 0.02;  // metres
  double k_d = 0.05;     // per metre
  double k_theta = 0.5;  // at the edge of the FOV
  double k_size = 0.5;   // for a one-sector obstacle

  double sigma(double d, double theta, int size) const {
    return sigma0 * (1.0 + k_d * d) * (1.0 + k_theta * theta) * (1.0 + k_size / size) /
           (1.0 + k_size);
  }
  double log_density_of_error(double error, double d, double theta, int size) const {
    return gaussian_log_density(error, sigma(d, theta, size));
  }
};

// Throws std::invalid_argument naming the offending parameter.
inline void check_model(const ConeSensorModel& m) {
  check_model(GaussianBeamModel{m.sigma0, m.k_d});
  if (!(m.k_theta >= 0.0) || !std::isfinite(m.k_theta))
    fail<std::invalid_argument>("k_theta must be a non-negative finite number");
  if (!(m.k_size >= 0.0) || !std::isfinite(m.k_size))
    fail<std::invalid_argument>("k_size must be a non-negative finite number");
}

}  // namespace intgrid::core
