// Integer occupancy probabilities: the set S_eps (thesis 2.7). p_n is the
// probability whose log-odds is n * lambda, lambda = logit(1/2 + eps), so that
// Bayesian fusion F(p_i, p_j) = p_{i+j} is integer addition of indices.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace intgrid::core {

inline double logit(double p) {
  return std::log(p) - std::log1p(-p);
}
inline double logistic(double x) {
  return 1.0 / (1.0 + std::exp(-x));
}

// Saturating index addition: the whole of S_eps fusion.
template <class Index>
constexpr Index fuse_indices(Index a, Index b, int max_index) {
  return static_cast<Index>(std::clamp(int{a} + int{b}, -max_index, max_index));
}

// Cell-wise fusion of two index grids into out (which may alias a).
template <class Index>
void fuse_indices(std::span<const Index> a, std::span<const Index> b, std::span<Index> out,
                  int max_index) {
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = fuse_indices(a[i], b[i], max_index);
}

// Floating-point Bayesian fusion, the operation index addition replaces.
inline double fuse_probabilities(double p, double q) {
  const double num = p * q;
  const double den = num + (1.0 - p) * (1.0 - q);
  return den > 0.0 ? num / den : 0.5;
}

// Cell-wise Bayesian fusion of two probability grids into out (which may alias a).
inline void fuse_probabilities(std::span<const double> a, std::span<const double> b,
                               std::span<double> out) {
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = fuse_probabilities(a[i], b[i]);
}

// The largest index of a `bits`-bit S_eps grid; throws unless 2 <= bits <= 16.
int max_index_for_bits(int bits);

// An S_eps codec for indices of `bits` bits saturating at +-(2^(bits-1) - 1).
class SepsCodec {
 public:
  SepsCodec(int bits, double eps);

  // eps such that the most confident index p_max_index equals p_most.
  static SepsCodec for_confidence(int bits, double p_most);
  // eps such that p_levels equals pmax: a reading of probability pmax spans `levels` steps.
  static SepsCodec for_levels(int bits, double pmax, int levels);

  int bits() const { return bits_; }
  double eps() const { return eps_; }
  double lambda() const { return lambda_; }
  int max_index() const { return max_index_; }

  // p_n for any n (not only the representable ones).
  double probability(int n) const { return logistic(n * lambda_); }
  // The index of largest magnitude whose p_n lies between 1/2 and p: never more
  // confident than p. Saturates; NaN (no information) gives 0.
  int quantize_conservative(double p) const;
  // The index nearest p in log-odds. Saturates; NaN gives 0.
  int quantize_nearest(double p) const;
  int fuse(int a, int b) const { return fuse_indices(a, b, max_index_); }

 private:
  int bits_;
  double eps_;
  double lambda_;
  int max_index_;
  // The largest n <= max_index with p_-n >= q, for q <= 1/2.
  int steps_below_one_half(double q) const;

  // p_-n for n = 0..max_index, computed directly: quantization compares q = p
  // (p < 1/2) or q = 1 - p (p >= 1/2, exact in double) against them, so the
  // small probabilities keep their precision and both sides quantize alike.
  std::vector<double> empty_thresholds_;
};

}  // namespace intgrid::core
