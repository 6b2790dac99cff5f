#include "intgrid/core/ugamma.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

UGamma::UGamma(int bits, int steps_per_halving)
    : bits_(bits), steps_per_halving_(steps_per_halving) {
  if (bits < 8 || bits > 31) fail<std::invalid_argument>("U_gamma index width must be 8..31 bits");
  if (steps_per_halving < 1 || steps_per_halving > 4096)
    fail<std::invalid_argument>("U_gamma steps per halving must be 1..4096");
  ln_gamma_ = -std::log(2.0) / steps_per_halving;
  gamma_ = std::exp(ln_gamma_);
  zero_ = static_cast<UIndex>((std::int64_t{1} << (bits - 1)) - 1);
  min_ = static_cast<UIndex>(-(std::int64_t{1} << (bits - 1)));
  // Phi_plus(D) = round(-log_gamma(1 + gamma^D)): ln(1 + gamma^D) / -ln(gamma), for every
  // difference |i - j| of two indices, 0 .. zero_ - 1 - min_, until it rounds to 0.
  for (std::int64_t d = 0; d < std::int64_t{zero_} - min_; ++d) {
    const double v = std::log1p(std::exp(ln_gamma_ * static_cast<double>(d))) / -ln_gamma_;
    const auto rounded = static_cast<UIndex>(std::lround(v));
    if (rounded == 0) break;
    phi_plus_.push_back(rounded);
  }
  // Phi_minus(i) = round(log_gamma(1 - gamma^i)); Phi_minus(0) is the code of 0. Not
  // saturated: Phi_minus(1) is about steps * log2(steps / ln 2), which may pass zero_ (about
  // 51,300 for 4096 steps, so it fits an index).
  phi_minus_.push_back(zero_);
  for (std::int64_t i = 1; i < zero_; ++i) {
    const double v = std::log(-std::expm1(ln_gamma_ * static_cast<double>(i))) / ln_gamma_;
    const auto rounded = static_cast<UIndex>(std::lround(v));
    if (rounded == 0) break;
    phi_minus_.push_back(rounded);
  }
}

UIndex UGamma::from_log(double ln_u) const {
  if (std::isnan(ln_u)) fail<std::invalid_argument>("U_gamma: log of a probability is NaN");
  if (ln_u == -std::numeric_limits<double>::infinity()) return zero_;
  const double v = std::round(ln_u / ln_gamma_);
  if (v >= static_cast<double>(zero_)) return zero_;
  if (v <= static_cast<double>(min_)) return min_;
  return static_cast<UIndex>(v);
}

UIndex UGamma::from_probability(double p) const {
  if (std::isnan(p) || p < 0.0) fail<std::invalid_argument>("U_gamma: probability must be >= 0");
  return p == 0.0 ? zero_ : from_log(std::log(p));
}

double UGamma::to_log(UIndex i) const {
  return i >= zero_ ? -std::numeric_limits<double>::infinity() : ln_gamma_ * static_cast<double>(i);
}

double UGamma::to_probability(UIndex i) const {
  return i >= zero_ ? 0.0 : std::exp(to_log(i));
}

}  // namespace intgrid::core
