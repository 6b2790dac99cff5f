// The two arithmetics of the SLAM's probabilities (docs/algorithms.md 6): double precision, and
// U_gamma indices. Each offers the same operations, so GridSlamEngine is written once; only their
// construction (make_probabilities, setup.cpp) needs floating point in the integer case.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "intgrid/core/seps.hpp"
#include "intgrid/core/ugamma.hpp"

namespace intgrid::slam {

struct DoubleProbabilities {
  using P = double;
  using Weight = double;  // what the mean of the pose grid is weighted with

  core::SepsCodec codec{8, 0.1};
  double floor = 1e-3;
  double cutoff = 0.01;
  double prune = 1e-40;
  std::vector<double> occupied_of, empty_of;  // p_n and 1 - p_n, n = -max..max at [n + max]
  int max_seps = 0;

  P one() const { return 1.0; }
  P zero() const { return 0.0; }
  P half() const { return 0.5; }
  P mul(P a, P b) const { return a * b; }
  P div(P a, P b) const { return b > 0.0 ? a / b : 0.0; }
  P add(P a, P b) const { return a + b; }
  P complement(P a) const { return a < 1.0 ? 1.0 - a : 0.0; }
  bool is_zero(P a) const { return !(a > 0.0); }
  // A scan's joint likelihood, value * 2^exponent: the product of many beams can pass below
  // the smallest double before the tempering root brings it back.
  struct Joint {
    double value = 1.0;
    int exponent = 0;
  };
  void multiply_into(Joint& j, P a) const {
    j.value *= a;
    if (j.value < 0x1p-1000) {  // only then, so that products above it round as plain ones
      j.value *= 0x1p1000;
      j.exponent -= 1000;
    }
  }
  // The joint likelihood to the power 1 / k.
  P root_of(const Joint& j, int k) const {
    const P r = k == 1 ? j.value : std::pow(j.value, 1.0 / k);
    return j.exponent == 0 ? r : r * std::exp2(static_cast<double>(j.exponent) / k);
  }
  bool below_cutoff(P a) const { return a < cutoff; }
  bool below_prune(P a) const { return a < prune; }
  bool more_probable(P a, P b) const { return a > b; }
  // exp(-e^2 / (2 s^2)): an unnormalized Gaussian of the error e, variance s^2.
  P gaussian(std::int64_t e2, std::int64_t s2) const {
    return std::exp(-0.5 * static_cast<double>(e2) / static_cast<double>(s2));
  }
  P occupied(int n) const { return occupied_of[static_cast<std::size_t>(n + max_seps)]; }
  P empty(int n) const { return empty_of[static_cast<std::size_t>(n + max_seps)]; }
  // prod P_M(e) over the cells a ray crosses, factor by factor in the ray's order.
  using EmptyProduct = double;
  EmptyProduct empty_factor(int n) const { return empty(n); }
  EmptyProduct empty_product_start() const { return 1.0; }
  // products[i] *= factors[i] for i < n (the arrays do not overlap).
  static void multiply_empty(EmptyProduct* __restrict products,
                             const EmptyProduct* __restrict factors, int n) {
    for (int i = 0; i < n; ++i) products[i] *= factors[i];
  }
  P empty_product(EmptyProduct product) const { return product; }
  // The S_eps index of P(o) = occ / (occ + emp), conservatively.
  int seps_of(P occ, P emp) const {
    const double total = occ + emp;
    return total > 0.0 ? codec.quantize_conservative(occ / total) : 0;
  }
  Weight weight(P a) const { return a; }
};

struct IndexProbabilities {
  using P = core::UIndex;
  using Weight = std::int64_t;

  core::UGamma u{16, 16};
  core::UIndex floor = 0;
  core::UIndex cutoff = 0;
  core::UIndex prune = 0;
  std::vector<core::UIndex> occupied_of, empty_of;  // as DoubleProbabilities, in U_gamma
  int max_seps = 0;
  std::int64_t gaussian_q20 = 0;         // 2^20 / (2 ln(1/gamma))
  std::int64_t seps_per_step_q16 = 0;    // 2^16 ln(1/gamma) / lambda_seps
  std::vector<std::int64_t> weight_q20;  // 2^20 gamma^i, i = 0.. until it rounds to 0

  P one() const { return 0; }
  P zero() const { return u.zero(); }
  P half() const { return u.steps_per_halving(); }
  P mul(P a, P b) const { return u.multiply(a, b); }
  P div(P a, P b) const { return u.divide(a, b); }
  P add(P a, P b) const { return u.add(a, b); }
  P complement(P a) const { return u.complement(a); }
  bool is_zero(P a) const { return u.is_zero(a); }
  // A scan's joint likelihood: the sum of its beams' indices in 64 bits, saturated only after
  // the tempering root, as the product of many beams passes the smallest index.
  struct Joint {
    std::int64_t sum = 0;
    bool zero = false;
  };
  void multiply_into(Joint& j, P a) const {
    if (u.is_zero(a))
      j.zero = true;
    else
      j.sum += a;
  }
  P root_of(const Joint& j, int k) const { return j.zero ? u.zero() : u.saturate(j.sum / k); }
  bool below_cutoff(P a) const { return a > cutoff; }
  bool below_prune(P a) const { return a > prune; }
  bool more_probable(P a, P b) const { return a < b; }
  P gaussian(std::int64_t e2, std::int64_t s2) const {
    return u.saturate((e2 * gaussian_q20 / s2 + (1 << 19)) >> 20);
  }
  P occupied(int n) const { return occupied_of[static_cast<std::size_t>(n + max_seps)]; }
  P empty(int n) const { return empty_of[static_cast<std::size_t>(n + max_seps)]; }
  // prod P_M(e) over the cells a ray crosses: a plain sum of indices, saturated once at the end
  // (no P_M(e) is 0, so no term is the zero code).
  using EmptyProduct = std::int64_t;
  EmptyProduct empty_factor(int n) const { return empty(n); }
  EmptyProduct empty_product_start() const { return 0; }
  // sums[i] += factors[i] for i < n (the arrays do not overlap). Out of line: inlined into the
  // localization, which is compiled with general registers only, it ran 20% slower.
  [[gnu::noinline]] static void multiply_empty(EmptyProduct* __restrict sums,
                                               const EmptyProduct* __restrict factors, int n) {
    for (int i = 0; i < n; ++i) sums[i] += factors[i];
  }
  P empty_product(EmptyProduct sum) const { return u.saturate(sum); }
  // log-odds ln(occ / emp) = (emp - occ) ln(1/gamma), truncated toward zero in S_eps steps.
  int seps_of(P occ, P emp) const {
    if (u.is_zero(occ)) return u.is_zero(emp) ? 0 : -max_seps;
    if (u.is_zero(emp)) return max_seps;
    const std::int64_t scaled = (std::int64_t{emp} - occ) * seps_per_step_q16;
    const std::int64_t n = scaled >= 0 ? scaled >> 16 : -((-scaled) >> 16);
    return static_cast<int>(n > max_seps ? max_seps : n < -max_seps ? -max_seps : n);
  }
  Weight weight(P a) const {
    if (a < 0) return weight_q20[0];
    return static_cast<std::size_t>(a) < weight_q20.size() ? weight_q20[static_cast<std::size_t>(a)]
                                                           : 0;
  }
};

}  // namespace intgrid::slam
