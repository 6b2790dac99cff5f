#include "intgrid/core/seps.hpp"

#include <string>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

int max_index_for_bits(int bits) {
  if (bits < 2 || bits > 16)
    fail<std::invalid_argument>("index width must be 2..16 bits, got " + std::to_string(bits));
  return (1 << (bits - 1)) - 1;
}

SepsCodec::SepsCodec(int bits, double eps)
    : bits_(bits), eps_(eps), lambda_(0.0), max_index_(max_index_for_bits(bits)) {
  if (!(eps > 0.0 && eps < 0.5))
    fail<std::invalid_argument>("eps must lie in (0, 1/2), got " + std::to_string(eps));
  lambda_ = logit(0.5 + eps);
  for (int n = 0; n <= max_index_; ++n) empty_thresholds_.push_back(probability(-n));
  // Below some eps, 1/2 + eps rounds to 1/2 (or p_-1 to 1/2): the indices would have no step.
  if (!(empty_thresholds_[1] < empty_thresholds_[0]))
    fail<std::invalid_argument>("eps is too small: 1/2 plus it rounds to 1/2 in double precision");
}

SepsCodec SepsCodec::for_confidence(int bits, double p_most) {
  if (!(p_most > 0.5 && p_most < 1.0))
    fail<std::invalid_argument>("the most confident probability must lie in (1/2, 1)");
  return SepsCodec(bits, logistic(logit(p_most) / max_index_for_bits(bits)) - 0.5);
}

SepsCodec SepsCodec::for_levels(int bits, double pmax, int levels) {
  if (!(pmax > 0.5 && pmax < 1.0)) fail<std::invalid_argument>("Pmax must lie in (1/2, 1)");
  if (levels < 1) fail<std::invalid_argument>("the number of levels must be at least 1");
  return SepsCodec(bits, logistic(logit(pmax) / levels) - 0.5);
}

int SepsCodec::steps_below_one_half(double q) const {
  // A first guess from the log-odds, corrected against the exact thresholds.
  const double guess = std::trunc(-logit(q) / lambda_);
  int n = static_cast<int>(std::clamp(guess, 0.0, static_cast<double>(max_index_)));
  while (n < max_index_ && empty_thresholds_[std::size_t(n + 1)] >= q) ++n;
  while (n > 0 && empty_thresholds_[std::size_t(n)] < q) --n;
  return n;
}

int SepsCodec::quantize_conservative(double p) const {
  if (std::isnan(p)) return 0;
  if (p <= 0.0) return -max_index_;
  if (p >= 1.0) return max_index_;
  return p >= 0.5 ? steps_below_one_half(1.0 - p) : -steps_below_one_half(p);
}

int SepsCodec::quantize_nearest(double p) const {
  if (std::isnan(p)) return 0;
  if (p <= 0.0) return -max_index_;
  if (p >= 1.0) return max_index_;
  const double n = std::round(logit(p) / lambda_);
  return static_cast<int>(std::clamp(n, double(-max_index_), double(max_index_)));
}

}  // namespace intgrid::core
