// Synthesizable C++ of the sectoral ISM kernel (docs/hardware.md, kernel 2): the S_eps index of
// every polar cell for one reading, bit for bit golden's ism_kernel_indices
// (golden/kernel/include/intgrid/kernel/ism_kernel.hpp). The same operations in the same order as
// golden's sectoral_ism_rings with KernelLogArith: per ring, the class densities, then for each
// condition v the sum over the classes in ascending order times the ring prior; the suffix
// sums over the rings downward; the prefix sums upward with the (ring, sector) outputs.
//
// Config is a generated configuration struct (testbench/ism_kernel_export.cpp): static
// constexpr sizes, the RTL's word widths and the tables as constexpr std::array. Everything here
// has a fixed width and a static size; every loop bound is a Config constant; no floating point,
// no dynamic memory, no recursion, no I/O; nothing but standard headers.
//
// Widths are the RTL's (rtl/sectoral_ism_*.sv), held in fixed_int.hpp's sint/uint:
//   reading     uint<reading_bits>
//   log value   IsmLog: sint<log_bits> (LOG_W) and a log-0 flag, the RTL's {zero, value}
//   |z - d_r|   uint<e_bits> (E_W) inside the window;  its square uint<sq_bits> (SQ_W)
//   quad_coef   uint<coef_bits> (COEF_W);  log_norm sint<norm_bits>;  log_weight sint<weight_bits>
//   Phi - 1     uint<phi_bits> (every Phi >= 1, as the RTL's ROM holds it)
//   odds        sint<log_bits + 1>, their magnitude uint<log_bits + 1>
//   thresholds  uint<thr_bits>;  bucket counts uint<bucket_bits>;  index sint<index_bits>
// Loop counters and table addresses stay `int`: their bounds are constants, from which a
// synthesis tool sizes them.
#pragma once

#include <cstdint>

#include "hls/fixed_int.hpp"
#include "hls/hls_pragma.hpp"

namespace intgrid::hls {

// The widths of a configuration that its generated struct does not list: those of its tables,
// as golden's derive_ism_hw computes them (testbench/sectoral_ism_hls_test.cpp compares).
template <class Config>
struct IsmWidths {
  static constexpr int log_bits = Config::log_bits;
  static constexpr int norm_bits = [] {
    std::int64_t lo = 0, hi = 0;
    for (const std::int32_t n : Config::log_norm) {
      lo = n < lo ? n : lo;
      hi = n > hi ? n : hi;
    }
    return signed_bits(lo, hi);
  }();
  static constexpr int weight_bits = [] {  // finite weights; log 0 is the RTL ROM's flag bit
    std::int64_t lo = 0, hi = 0;
    for (const std::int32_t w : Config::log_weight)
      if (w != Config::log_zero) {
        lo = w < lo ? w : lo;
        hi = w > hi ? w : hi;
      }
    return signed_bits(lo, hi);
  }();
  static constexpr int phi_count = static_cast<int>(Config::log_add.size());
  static constexpr int phi_bits = [] {
    std::int64_t hi = 0;
    for (const std::uint16_t phi : Config::log_add) hi = phi - 1 > hi ? phi - 1 : hi;
    return unsigned_bits(hi);
  }();
  static constexpr int thr_bits = unsigned_bits(Config::thresholds.back());
  static constexpr int bucket_bits = unsigned_bits(Config::max_index);
  // A ring number 0 .. rings + 1.
  static constexpr int ring_bits = unsigned_bits(Config::rings + 1);
};

// A log value as the RTL holds it: a log_bits-bit two's-complement value and a log-0 flag.
// It converts from and to golden's int32 encoding (log 0 = Config::log_zero), so callers that
// hold int32 log values pass and receive them unchanged; a finite value must lie within
// +-(2^(log_bits-1) - 1), which every value of the kernel does (Config::log_bound).
template <class Config>
struct IsmLog {
  using Value = sint<Config::log_bits>;
  bool zero = true;
  Value value{};

  constexpr IsmLog() = default;
  constexpr IsmLog(bool is_zero, Value v) : zero(is_zero), value(v) {}
  constexpr IsmLog(std::int32_t golden)  // NOLINT(google-explicit-constructor)
      : zero(golden == Config::log_zero), value(golden == Config::log_zero ? 0 : golden) {}
  constexpr operator std::int32_t() const {  // NOLINT(google-explicit-constructor)
    return zero ? Config::log_zero : static_cast<std::int32_t>(value);
  }
  static constexpr IsmLog log_zero() { return IsmLog{}; }
};

// log2(2^a + 2^b) in the kernel's fixed point: one Phi ROM lookup (rtl/sectoral_ism_log_add.sv:
// compare and subtract, then the ROM read and the sum; 2 cycles there).
template <class Config>
constexpr IsmLog<Config> ism_log_add(IsmLog<Config> a, IsmLog<Config> b) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  using W = IsmWidths<Config>;
  if (a.zero) return b;
  if (b.zero) return a;
  const bool a_ge_b = a.value >= b.value;
  const sint<W::log_bits> hi = a_ge_b ? a.value : b.value;
  const sint<W::log_bits> lo = a_ge_b ? b.value : a.value;
  const uint<W::log_bits> distance = hi - lo;  // 0 .. 2^log_bits - 1
  if (distance >= W::phi_count) return IsmLog<Config>{false, hi};
  const uint<W::phi_bits> phi_m1 = Config::log_add[static_cast<std::uint32_t>(distance)] - 1;
  return IsmLog<Config>{false, hi + uint<1>(1) + phi_m1};
}

// log2(2^a * 2^b): an addition, log 0 absorbing. (Golden also saturates a sum at or below its
// int32 log 0 to log 0; two log_bits-bit values never sum that low.)
template <class Config>
constexpr IsmLog<Config> ism_log_mul(IsmLog<Config> a, IsmLog<Config> b) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  if (a.zero || b.zero) return IsmLog<Config>::log_zero();
  return IsmLog<Config>{false, a.value + b.value};
}

// The S_eps index of the log-odds num - den: the count of thresholds at or below |odds|,
// with its sign. No search: the bucket table gives the count below |odds| rounded down to a
// multiple of 2^bucket_shift, and the thresholds lie at least that far apart, so one
// comparison finishes it (rtl/sectoral_ism_index.sv).
template <class Config>
constexpr sint<Config::index_bits> ism_index_of_log_odds(IsmLog<Config> num, IsmLog<Config> den) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  using W = IsmWidths<Config>;
  constexpr uint<W::bucket_bits> kMax = Config::max_index;
  if (num.zero && den.zero) return 0;
  if (num.zero) return -kMax;
  if (den.zero) return kMax;
  const sint<W::log_bits + 1> odds = num.value - den.value;
  const uint<W::log_bits + 1> mag = magnitude(odds);
  const auto bucket = shr<Config::bucket_shift>(mag);
  uint<W::bucket_bits> n = kMax;
  if (bucket < Config::bucket_count) {
    const uint<W::bucket_bits> base = Config::threshold_bucket[static_cast<std::uint32_t>(bucket)];
    n = base;
    if (base < kMax) {
      const uint<W::thr_bits> next = Config::thresholds[static_cast<std::uint32_t>(base)];
      if (next <= mag) n = base + uint<1>(1);
    }
  }
  return odds < 0 ? sint<Config::index_bits>(-n) : sint<Config::index_bits>(n);
}

// log2 p(z | d_r, class c): minus the quadratic term minus the normalization, log 0 past the
// window (rtl/sectoral_ism_density.sv).
template <class Config>
constexpr IsmLog<Config> ism_log_density(uint<Config::reading_bits> reading, int ring, int c) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  using W = IsmWidths<Config>;
  const uint<W::ring_bits> r = ring;
  const auto error = reading - shl<Config::reading_frac_bits>(r);  // exact
  constexpr std::int64_t kWindow = std::int64_t{Config::window_cells} << Config::reading_frac_bits;
  if (magnitude(error) >= kWindow) return IsmLog<Config>::log_zero();
  const uint<Config::e_bits> e = magnitude(error);
  const uint<Config::sq_bits> square = e * e;
  const int at = (ring - 1) * Config::classes + c;
  const uint<Config::coef_bits> coef = Config::quad_coef[static_cast<std::uint32_t>(at)];
  const sint<W::norm_bits> norm = Config::log_norm[static_cast<std::uint32_t>(at)];
  const uint<W::log_bits> quad = shr<Config::quad_shift>(square * coef);
  return IsmLog<Config>{false, -quad - norm};
}

// log_weight[v][c], its finite values in weight_bits.
template <class Config>
constexpr IsmLog<Config> ism_log_weight(int v, int c) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  const std::int32_t w = Config::log_weight[static_cast<std::uint32_t>(v * Config::classes + c)];
  if (w == Config::log_zero) return IsmLog<Config>::log_zero();
  return IsmLog<Config>{false, sint<IsmWidths<Config>::weight_bits>(w)};
}

// The accumulation over the classes: accumulator v receives its class-c term in step c * V + v,
// so consecutive steps go to different accumulators and one accumulator is read again only V
// steps after its last write (the RTL's sum pipeline, rtl/sectoral_ism_setup.sv). The log-add
// takes kIsmLogAddLatency cycles in the RTL (stage 1: compare and subtract LOG_W + 1 bits and
// address the Phi ROM; stage 2: the synchronous ROM read and the sum), so a loop-carried distance
// of V >= kIsmAccumulatorDistance > that latency lets the loop start one step per cycle.
// kIsmAccumulatorDistance is the distance the DEPENDENCE pragma below declares (a lower bound
// of the true distance V, hence safe).
inline constexpr int kIsmLogAddLatency = 2;
inline constexpr int kIsmAccumulatorDistance = 3;

// The kernel: out[(r - 1) * bins + a] = the S_eps index of polar cell (ring r, bin a), written
// once each in that order (so `out` may be a stream port). Cell is any integer type that holds
// index_bits (int16_t for golden's layout, int8_t at a port).
template <class Config, class Cell>
void sectoral_ism_kernel(std::uint32_t reading, Cell out[Config::rings * Config::bins]) {
  constexpr int R = Config::rings;
  constexpr int Ns = Config::sectors;
  constexpr int C = Config::classes;
  constexpr int V = Config::conditions;
  static_assert(V >= kIsmAccumulatorDistance && kIsmAccumulatorDistance > kIsmLogAddLatency,
                "the accumulators must outnumber the log-add's latency for II = 1");
  using Log = IsmLog<Config>;
  const uint<Config::reading_bits> z = reading;
  // Every log value starts as log 0 (IsmLog's default).
  Log ring_term[R + 1];         // T_r, r = 1..R
  Log conditioned[R * 2 * Ns];  // per ring: Ns occupied, then Ns emptied sums
  Log after[R + 1];             // sum of T over the rings past r (log 0 past the last)
  Log density[C];
  Log accumulator[V];
  INTGRID_HLS_PRAGMA("HLS ARRAY_PARTITION variable=density complete")
  INTGRID_HLS_PRAGMA("HLS ARRAY_PARTITION variable=accumulator complete")
  // Ring terms: per ring the class densities, then the V sums over the classes, interleaved.
  for (int r = 1; r <= R; ++r) {
    for (int c = 0; c < C; ++c) {
      INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
      density[c] = ism_log_density<Config>(z, r, c);
    }
    // The prior 2^-M_r, M_r = (r - 1) * bins: -(r - 1) * bins << log_frac_bits.
    const uint<IsmWidths<Config>::ring_bits> r_index = r - 1;
    const Log prior{false, -shl<Config::log_frac_bits>(
                               r_index * uint<unsigned_bits(Config::bins)>(Config::bins))};
    int c = 0, v = 0;  // step c * V + v
    for (int step = 0; step < C * V; ++step) {
      INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
      INTGRID_HLS_PRAGMA(
          "HLS DEPENDENCE variable=accumulator type=inter direction=RAW distance=3 dependent=true")
      const Log term = ism_log_mul<Config>(density[c], ism_log_weight<Config>(v, c));
      const Log sum = ism_log_add<Config>(c == 0 ? Log::log_zero() : accumulator[v], term);
      accumulator[v] = sum;
      if (c == C - 1) {
        const Log weighted = ism_log_mul<Config>(sum, prior);
        if (v == 0)
          ring_term[r] = weighted;
        else
          conditioned[(r - 1) * 2 * Ns + (v - 1)] = weighted;
      }
      if (++v == V) {
        v = 0;
        ++c;
      }
    }
  }
  // Suffix sums, downward: a recurrence through the log-add, one step per latency (the RTL's
  // suffix phase takes 2 cycles a ring too).
  for (int r = R - 1; r >= 1; --r) {
    INTGRID_HLS_PRAGMA("HLS PIPELINE II=2")
    after[r] = ism_log_add<Config>(after[r + 1], ring_term[r + 1]);
  }
  Log before = Log::log_zero();
  constexpr sint<Config::log_bits> kTwo = std::int32_t{1} << Config::log_frac_bits;  // log2(2)
  // Prefix sums upward, and the outputs of every (ring, sector).
  for (int r = 1; r <= R; ++r) {
    const Log beyond = ism_log_mul<Config>(Log{false, kTwo}, after[r]);
    for (int j = 0; j < Ns; ++j) {
      const Log num = ism_log_add<Config>(before, conditioned[(r - 1) * 2 * Ns + j]);
      const Log den = ism_log_add<Config>(
          ism_log_add<Config>(before, conditioned[(r - 1) * 2 * Ns + Ns + j]), beyond);
      const sint<Config::index_bits> index = ism_index_of_log_odds<Config>(num, den);
      for (int k = 0; k < Config::bins_per_sector; ++k) {
        INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
        out[(r - 1) * Config::bins + j * Config::bins_per_sector + k] = index;
      }
    }
    before = ism_log_add<Config>(before, ring_term[r]);
  }
}

}  // namespace intgrid::hls
