// Synthesizable C++ of the sectoral ISM kernel (docs/hardware.md, kernel 2): the S_eps index of
// every polar cell for one reading, bit for bit golden's ism_kernel_indices
// (golden/kernel/include/intgrid/kernel/ism_kernel.hpp). The same operations in the same order as
// golden's sectoral_ism_rings with KernelLogArith: per ring, the class densities, then for each
// condition v the sum over the classes in ascending order times the ring prior; the suffix
// sums over the rings downward; the prefix sums upward with the (ring, sector) outputs.
//
// Config is a generated configuration struct (testbench/ism_kernel_export.cpp): static
// constexpr sizes and the tables as constexpr std::array. Everything here has a fixed width
// and a static size; every loop bound is a Config constant; no floating point, no dynamic
// memory, no recursion, no I/O; nothing but <cstdint>.
//
// Widths (the RTL narrows them to what the configuration provably needs, Config::log_bits):
//   reading    uint32_t, Config::reading_bits used; fixed point with reading_frac_bits
//   log values int32_t, Q.log_frac_bits base-2 logarithms; log 0 = Config::log_zero (-2^30)
//   error      int64_t / uint64_t: |reading - ring|, its square times quad_coef (< 2^63)
//   odds       int64_t: the difference of two log values
//   index      int16_t, Config::index_bits used (+-max_index)
#pragma once

#include <cstdint>

// HLS directives for a synthesis tool (Vitis HLS defines __SYNTHESIS__); nothing elsewhere.
#if defined(__SYNTHESIS__)
#define INTGRID_HLS_PRAGMA(x) _Pragma(#x)
#else
#define INTGRID_HLS_PRAGMA(x)
#endif

namespace intgrid::hls {

// log2(2^a + 2^b) in the kernel's fixed point: one Phi ROM lookup.
template <class Config>
inline std::int32_t ism_log_add(std::int32_t a, std::int32_t b) {
  if (a == Config::log_zero) return b;
  if (b == Config::log_zero) return a;
  const std::int32_t hi = a > b ? a : b;
  const std::int32_t lo = a > b ? b : a;
  const std::int64_t d = std::int64_t{hi} - lo;  // >= 0
  constexpr std::int64_t n = static_cast<std::int64_t>(Config::log_add.size());
  return d < n ? static_cast<std::int32_t>(hi + Config::log_add[static_cast<std::uint32_t>(d)])
               : hi;
}

// log2(2^a * 2^b): an addition, log 0 absorbing, saturating to log 0 at or below it.
template <class Config>
inline std::int32_t ism_log_mul(std::int32_t a, std::int32_t b) {
  if (a == Config::log_zero || b == Config::log_zero) return Config::log_zero;
  const std::int64_t p = std::int64_t{a} + b;
  return p <= Config::log_zero ? Config::log_zero : static_cast<std::int32_t>(p);
}

// The S_eps index of the log-odds num - den: the count of thresholds at or below |odds|,
// with its sign. No search: the bucket table gives the count below |odds| rounded down to a
// multiple of 2^bucket_shift, and the thresholds lie at least that far apart, so one
// comparison finishes it.
template <class Config>
inline int ism_index_of_log_odds(std::int32_t num, std::int32_t den) {
  if (num == Config::log_zero && den == Config::log_zero) return 0;
  if (num == Config::log_zero) return -Config::max_index;
  if (den == Config::log_zero) return Config::max_index;
  const std::int64_t odds = std::int64_t{num} - den;
  const std::uint64_t mag = static_cast<std::uint64_t>(odds < 0 ? -odds : odds);
  const std::uint64_t bucket = mag >> Config::bucket_shift;
  int n = Config::max_index;
  if (bucket < static_cast<std::uint64_t>(Config::bucket_count)) {
    const int base = Config::threshold_bucket[static_cast<std::uint32_t>(bucket)];
    n = base;
    if (base < Config::max_index &&
        static_cast<std::int64_t>(Config::thresholds[static_cast<std::uint32_t>(base)]) <=
            static_cast<std::int64_t>(mag))
      n = base + 1;
  }
  return odds < 0 ? -n : n;
}

// log2 p(z | d_r, class c): minus the quadratic term minus the normalization, log 0 past the
// window.
template <class Config>
inline std::int32_t ism_log_density(std::uint32_t reading, int ring, int c) {
  const std::int64_t error =
      std::int64_t{reading} - (std::int64_t{ring} << Config::reading_frac_bits);
  const std::uint64_t mag = static_cast<std::uint64_t>(error < 0 ? -error : error);
  if (mag >= (std::uint64_t(Config::window_cells) << Config::reading_frac_bits))
    return Config::log_zero;
  const int at = (ring - 1) * Config::classes + c;
  const std::uint64_t quad =
      (mag * mag * Config::quad_coef[static_cast<std::uint32_t>(at)]) >> Config::quad_shift;
  return static_cast<std::int32_t>(-static_cast<std::int64_t>(quad) -
                                   Config::log_norm[static_cast<std::uint32_t>(at)]);
}

// The kernel: out[(r - 1) * bins + a] = the S_eps index of polar cell (ring r, bin a).
template <class Config>
void sectoral_ism_kernel(std::uint32_t reading, std::int16_t (&out)[Config::rings * Config::bins]) {
  constexpr int R = Config::rings;
  constexpr int Ns = Config::sectors;
  constexpr int C = Config::classes;
  constexpr int V = Config::conditions;
  constexpr std::int32_t Z = Config::log_zero;
  std::int32_t ring_term[R + 2];         // T_r
  std::int32_t conditioned[R * 2 * Ns];  // per ring: Ns occupied, then Ns emptied sums
  std::int32_t after[R + 2];             // sum of T over the rings past r
  std::int32_t density[C];
  for (int r = 0; r < R + 2; ++r) {
    ring_term[r] = Z;
    after[r] = Z;
  }
  // Ring terms: per ring the class densities, then the V sums over the classes.
  for (int r = 1; r <= R; ++r) {
    for (int c = 0; c < C; ++c) density[c] = ism_log_density<Config>(reading, r, c);
    const std::int32_t prior =
        static_cast<std::int32_t>(-((std::int64_t{r} - 1) * Config::bins << Config::log_frac_bits));
    for (int v = 0; v < V; ++v) {
      std::int32_t sum = Z;
      for (int c = 0; c < C; ++c) {
        INTGRID_HLS_PRAGMA(HLS PIPELINE II = 1)
        sum = ism_log_add<Config>(
            sum, ism_log_mul<Config>(density[c],
                                     Config::log_weight[static_cast<std::uint32_t>(v * C + c)]));
      }
      sum = ism_log_mul<Config>(sum, prior);
      if (v == 0)
        ring_term[r] = sum;
      else
        conditioned[(r - 1) * 2 * Ns + (v - 1)] = sum;
    }
  }
  // Suffix sums, downward.
  for (int r = R - 1; r >= 1; --r) after[r] = ism_log_add<Config>(after[r + 1], ring_term[r + 1]);
  std::int32_t before = Z;
  constexpr std::int32_t two = std::int32_t{1} << Config::log_frac_bits;
  // Prefix sums upward, and the outputs of every (ring, sector).
  for (int r = 1; r <= R; ++r) {
    const std::int32_t beyond = ism_log_mul<Config>(two, after[r]);
    for (int j = 0; j < Ns; ++j) {
      const std::int32_t num = ism_log_add<Config>(before, conditioned[(r - 1) * 2 * Ns + j]);
      const std::int32_t den = ism_log_add<Config>(
          ism_log_add<Config>(before, conditioned[(r - 1) * 2 * Ns + Ns + j]), beyond);
      const auto index = static_cast<std::int16_t>(ism_index_of_log_odds<Config>(num, den));
      for (int k = 0; k < Config::bins_per_sector; ++k) {
        INTGRID_HLS_PRAGMA(HLS PIPELINE II = 1)
        out[(r - 1) * Config::bins + j * Config::bins_per_sector + k] = index;
      }
    }
    before = ism_log_add<Config>(before, ring_term[r]);
  }
}

}  // namespace intgrid::hls
