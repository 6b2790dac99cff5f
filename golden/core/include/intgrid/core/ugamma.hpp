// Probabilities as integer exponents: the set U_gamma (docs/algorithms.md 5, thesis 3.4-3.5).
// u_n = gamma^n with 0 < gamma < 1, so an index is an integer exponent: multiplication and
// division are index addition and subtraction, addition and additive inversion are table
// lookups (Zech logarithms). Indices are signed, because unnormalized sums may exceed 1; the
// largest index is the code of probability 0.
//
// The operations are inline and use only integers, so that code built on them carries no
// floating point; only building the tables (UGamma's constructor) and the conversions to and
// from double use it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace intgrid::core {

using UIndex = std::int32_t;

class UGamma {
 public:
  // gamma = 2^(-1 / steps_per_halving); indices of `bits` bits, so they lie in
  // [-2^(bits-1), 2^(bits-1) - 1] and 2^(bits-1) - 1 is the code of 0. Throws
  // std::invalid_argument unless 8 <= bits <= 31 and 1 <= steps_per_halving <= 4096.
  explicit UGamma(int bits = 16, int steps_per_halving = 16);

  int bits() const { return bits_; }
  int steps_per_halving() const { return steps_per_halving_; }
  double gamma() const { return gamma_; }
  UIndex zero() const { return zero_; }
  UIndex min_index() const { return min_; }
  bool is_zero(UIndex i) const { return i >= zero_; }

  // i (x) j = i + j: probability 0 absorbs, and results saturate into the index range.
  UIndex multiply(UIndex i, UIndex j) const {
    if (i >= zero_ || j >= zero_) return zero_;
    return saturate(std::int64_t{i} + j);
  }
  // i (/) j = i - j, for j not the code of 0 (dividing 0 gives 0).
  UIndex divide(UIndex i, UIndex j) const {
    if (i >= zero_) return zero_;
    return saturate(std::int64_t{i} - j);
  }
  // i (+) j = min(i, j) - Phi_plus(|i - j|).
  UIndex add(UIndex i, UIndex j) const {
    if (i >= zero_) return j;
    if (j >= zero_) return i;
    const std::int64_t d = i > j ? std::int64_t{i} - j : std::int64_t{j} - i;
    const UIndex low = std::min(i, j);
    if (d >= static_cast<std::int64_t>(phi_plus_.size())) return low;
    return saturate(std::int64_t{low} - phi_plus_[static_cast<std::size_t>(d)]);
  }
  // The index of 1 - u_i, for 0 <= u_i <= 1 (i >= 0; a negative i is taken as 1); the zero
  // code when 1 - u_i is below the smallest non-zero probability.
  UIndex complement(UIndex i) const {
    if (i <= 0) return zero_;
    if (i >= zero_) return 0;
    return static_cast<UIndex>(std::min<std::int64_t>(phi_minus_unsaturated(i), zero_));
  }
  // Bayesian fusion u_i u_j / (u_i u_j + (1 - u_i)(1 - u_j)) of probabilities (i, j >= 0):
  // a = i + j, b = Phi_minus(i) + Phi_minus(j), F = a - (a (+) b) = max(x, 0) + Phi_plus(|x|)
  // with x = a - b. x is formed in 64 bits from the unsaturated tables, so a product a or b
  // past the zero code does not lose a result in range. 0 absorbs, then 1 does (1 fused with
  // 0, contradicting certainties, gives the zero code).
  UIndex fuse(UIndex i, UIndex j) const {
    if (i >= zero_ || j >= zero_) return zero_;
    if (i <= 0 || j <= 0) return 0;
    const std::int64_t x =
        std::int64_t{i} + j - phi_minus_unsaturated(i) - phi_minus_unsaturated(j);
    const std::int64_t d = x < 0 ? -x : x;
    const std::int64_t p = d < static_cast<std::int64_t>(phi_plus_.size())
                               ? phi_plus_[static_cast<std::size_t>(d)]
                               : 0;
    return saturate(std::max<std::int64_t>(x, 0) + p);
  }

  // Phi_plus(D) for D >= 0, 0 past the table.
  UIndex phi_plus(UIndex d) const {
    return d >= 0 && static_cast<std::size_t>(d) < phi_plus_.size()
               ? phi_plus_[static_cast<std::size_t>(d)]
               : 0;
  }
  std::size_t phi_plus_size() const { return phi_plus_.size(); }
  std::size_t phi_minus_size() const { return phi_minus_.size(); }

  // Conversions, for set-up and output only (double precision).
  // The nearest index of p >= 0 (p = 0 or below the smallest representable gives the zero code).
  UIndex from_probability(double p) const;
  // The index nearest -log_gamma applied to a natural log: ln u -> round(ln u / ln gamma).
  UIndex from_log(double ln_u) const;
  double to_probability(UIndex i) const;
  // ln(u_i); -inf for the zero code.
  double to_log(UIndex i) const;

  UIndex saturate(std::int64_t v) const {
    return static_cast<UIndex>(std::clamp<std::int64_t>(v, min_, zero_));
  }

 private:
  int bits_;
  int steps_per_halving_;
  double gamma_;
  double ln_gamma_;
  UIndex zero_;
  UIndex min_;
  // Phi_minus(i) for 1 <= i < zero_, not saturated to the zero code; 0 past the table.
  std::int64_t phi_minus_unsaturated(UIndex i) const {
    const auto k = static_cast<std::size_t>(i);
    return k < phi_minus_.size() ? phi_minus_[k] : 0;
  }

  // round(-log_gamma(1 + gamma^D)) >= 0 for D from 0 up to its last non-zero entry, which may
  // be past zero_ (differences of two indices reach 2^bits - 2).
  std::vector<UIndex> phi_plus_;
  // round(log_gamma(1 - gamma^i)) >= 0 for i from 1 up to its last non-zero entry or zero_ - 1,
  // unsaturated: it may exceed zero_ (complement saturates it, fuse does not); [0] is zero_.
  std::vector<UIndex> phi_minus_;
};

}  // namespace intgrid::core
