// The named hardware configurations of the sectoral ISM kernel (docs/hardware.md, kernel 2) and
// the word widths and schedule constants the hardware layers derive from golden's tables.
// Shared by the table generator (table_export.hpp, written out by testbench/ism_kernel_export)
// and the testbenches, so that both build exactly the same golden kernel for a name.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "intgrid/kernel/ism_kernel.hpp"

namespace intgrid::kernel {

struct IsmHwConfig {
  const char* name;
  core::ConeSensorModel model;
  core::SectoralGrid grid;
  int bits;  // S_eps index width
  double eps;
  IsmKernelFormat format;
};

// cone16: the defaults of docs/algorithms.md 3 (FOV 30 deg, 40 rings, 16 bins, 4 sectors, 5 cm);
// cone12: a narrow, coarse cone of 3 sectors with 6-bit indices.
inline const IsmHwConfig kIsmHwConfigs[] = {
    {"cone16", core::ConeSensorModel{}, core::SectoralGrid{}, 8, 0.05, IsmKernelFormat{}},
    {"cone12", core::ConeSensorModel{0.05, 0.0, 0.3, 0.2}, core::SectoralGrid{0.3, 25, 12, 3, 0.1},
     6, 0.2, IsmKernelFormat{}},
};

inline const IsmHwConfig& ism_hw_config(std::string_view name) {
  for (const IsmHwConfig& c : kIsmHwConfigs)
    if (name == c.name) return c;
  throw std::invalid_argument("unknown sectoral ISM hardware configuration: " + std::string(name));
}

inline IsmKernelTables make_ism_hw_kernel(const IsmHwConfig& c) {
  return make_ism_kernel(c.model, c.grid, core::SepsCodec(c.bits, c.eps), c.format);
}

// The RTL's reading port: 16 bits hold reach of both configurations (13568 and 9216).
inline constexpr int kIsmReadingBits = 16;

// Bits of an unsigned value / of a two's-complement range.
inline int unsigned_bits(std::uint64_t v) {
  int b = 1;
  while (b < 64 && (v >> b) != 0) ++b;
  return b;
}
inline int signed_bits(std::int64_t lo, std::int64_t hi) {
  int b = 2;
  while (b < 63 && (lo < -(std::int64_t{1} << (b - 1)) || hi >= (std::int64_t{1} << (b - 1)))) ++b;
  return b;
}

// What the RTL derives from the golden tables: word widths that provably hold every value
// the integer model forms, and the constants of its schedule.
struct IsmHwDerived {
  int window_units = 0;        // window_cells << reading_frac_bits
  int e_bits = 0;              // |z - d_r| inside the window, unsigned
  int sq_bits = 0;             // (z - d_r)^2 inside the window, unsigned
  int coef_bits = 0;           // quad_coef, unsigned
  int mul_b_bits = 0;          // the multiplier's digit operand: max(coef_bits, e_bits)
  int mul_digit_bits = 0;      // K: coefficient bits the multiplier takes per cycle
  int mul_digits = 0;          // ND = ceil(mul_b_bits / K)
  int quad_shift = 0;          // 2 reading_frac + quad_coef_frac - log_frac
  int norm_bits = 0;           // log_norm, signed
  int weight_bits = 0;         // finite log_weight, signed (the ROM word adds a zero flag)
  std::int64_t log_bound = 0;  // every finite log value lies in [-log_bound, log_bound]
  int log_bits = 0;            // LOG_W: signed word holding +-log_bound (differences use +1 bit)
  int phi_bits = 0;            // phi - 1, unsigned (every phi >= 1)
  int phi_addr_bits = 0;
  int thr_bits = 0;
  int bucket_shift = 0;  // 2^shift <= the least gap between consecutive thresholds
  int bucket_count = 0;  // (last threshold >> shift) + 1
  int bucket_bits = 0;   // holds 0..max_index
  int index_bits = 0;    // S_eps index word (the codec's bits)
};

inline IsmHwDerived derive_ism_hw(const IsmKernelTables& k, int index_bits) {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("sectoral ISM hardware: ") + what);
  };
  IsmHwDerived d;
  const IsmKernelFormat& f = k.format;
  const int C = k.classes, V = k.conditions, R = k.grid.rings, A = k.grid.bins;
  const std::int64_t one = std::int64_t{1} << f.log_frac_bits;
  d.window_units = k.window_cells << f.reading_frac_bits;
  const std::uint64_t e_max = std::uint64_t(d.window_units) - 1;
  d.e_bits = unsigned_bits(e_max);
  d.sq_bits = unsigned_bits(e_max * e_max);
  const std::uint32_t coef_max = *std::max_element(k.quad_coef.begin(), k.quad_coef.end());
  d.coef_bits = unsigned_bits(coef_max);
  d.mul_b_bits = std::max(d.coef_bits, d.e_bits);
  d.quad_shift = 2 * f.reading_frac_bits + f.quad_coef_frac_bits - f.log_frac_bits;
  // The density pre-fetch computes a ring's C densities while the sum pipeline runs the
  // previous ring's V * C steps; its last density is stored in slot cycle C * ND + 4, so
  // C * ND + 5 cycles must fit in V * C (rtl/sectoral_ism_density.sv).
  for (int kbits = 1; kbits <= d.mul_b_bits; ++kbits) {
    const int nd = (d.mul_b_bits + kbits - 1) / kbits;
    if (C * nd + 5 <= V * C) {
      d.mul_digit_bits = kbits;
      d.mul_digits = nd;
      break;
    }
  }
  require(d.mul_digit_bits > 0, "no multiplier digit width fits the ring schedule");
  require(V >= 3, "the accumulator loop needs at least 3 conditions");

  const auto [norm_lo, norm_hi] = std::minmax_element(k.log_norm.begin(), k.log_norm.end());
  d.norm_bits = signed_bits(*norm_lo, *norm_hi);
  std::int64_t w_lo = 0, w_hi = -(std::int64_t{1} << 40);
  for (const std::int32_t w : k.log_weight)
    if (w != IsmKernelTables::kLogZero) {
      w_lo = std::min<std::int64_t>(w_lo, w);
      w_hi = std::max<std::int64_t>(w_hi, w);
    }
  d.weight_bits = signed_bits(w_lo, std::max<std::int64_t>(w_hi, 0));

  // Bounds of every finite value of the recursion: densities, products with the weights,
  // sums over classes (each log-add adds at most phi(0) = 2^F), the ring prior, then the
  // sums over rings (before, after, beyond, the den chain): R + 3 more additions at most.
  const std::uint64_t quad_max = (e_max * e_max * coef_max) >> d.quad_shift;
  const std::int64_t dens_lo = -std::int64_t(quad_max) - *norm_hi, dens_hi = -*norm_lo;
  const std::int64_t sum_lo = dens_lo + w_lo - std::int64_t(R - 1) * A * one;
  const std::int64_t sum_hi = dens_hi + w_hi + std::int64_t(C - 1) * one;
  const std::int64_t all_hi = sum_hi + std::int64_t(R + 3) * one;
  d.log_bound = std::max(-sum_lo, all_hi);
  d.log_bits = signed_bits(-d.log_bound, d.log_bound);
  // Golden's saturation (a product at or below -2^30 becomes log 0) never happens inside
  // the bound, so the RTL's plain LOG_W-bit additions give golden's bits.
  require(d.log_bound < (std::int64_t{1} << 29), "log values leave the 2^29 range");

  require(k.log_add.front() == one, "phi(0) is not 1.0");
  d.phi_bits = unsigned_bits(std::uint64_t(k.log_add.front()) - 1);
  d.phi_addr_bits = unsigned_bits(k.log_add.size() - 1);
  d.thr_bits = unsigned_bits(std::uint64_t(k.thresholds.back()));
  require(k.thresholds.front() > 0, "the first threshold is not positive");
  std::int64_t gap = k.thresholds.front();
  for (std::size_t n = 1; n < k.thresholds.size(); ++n)
    gap = std::min<std::int64_t>(gap, k.thresholds[n] - k.thresholds[n - 1]);
  require(gap >= 1,
          "eps is too small for the log words' fraction: thresholds are not strictly "
          "increasing");
  d.bucket_shift = unsigned_bits(std::uint64_t(gap)) - 1;
  d.bucket_count = int(k.thresholds.back() >> d.bucket_shift) + 1;
  d.bucket_bits = unsigned_bits(std::uint64_t(k.max_index));
  d.index_bits = index_bits;
  require(k.reach < (1u << kIsmReadingBits), "reach does not fit the reading port");
  return d;
}

// bucket[b] = the number of thresholds below b << bucket_shift: with gaps of at least
// 2^shift, a magnitude m in bucket b passes thresholds bucket[b] and, if m reaches it,
// thresholds[bucket[b]].
inline std::vector<int> threshold_buckets(const IsmKernelTables& k, const IsmHwDerived& d) {
  std::vector<int> out(static_cast<std::size_t>(d.bucket_count));
  for (int b = 0; b < d.bucket_count; ++b) {
    const std::int64_t at = std::int64_t{b} << d.bucket_shift;
    out[static_cast<std::size_t>(b)] =
        int(std::lower_bound(k.thresholds.begin(), k.thresholds.end(), at) - k.thresholds.begin());
  }
  return out;
}

}  // namespace intgrid::kernel
