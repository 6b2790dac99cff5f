// Kernel 1, index fusion (S_eps), as synthesizable C++: y = sat(a + b) per cell, saturating at
// +-(2^(B-1) - 1), on beats of LANES cells of B-bit two's-complement indices.
//
// HLS rules kept here: fixed-width integers only (the lane sum in fixed_int.hpp's sint<B + 1>, as
// the RTL's adder), static sizes, constant loop bounds, no floating point, no dynamic memory, no
// recursion, no I/O. Only standard headers are included.
//
// A beat is packed exactly like the RTL's data bus (rtl/index_fusion.sv): lane l occupies bits
// [l*B + B-1 : l*B] of a LANES*B-bit vector, lane 0 in the least significant bits. The vector is
// held little-endian in 64-bit words (bit i of the bus is bit i%64 of word i/64); lanes may
// straddle two words. Bits above LANES*B in the last word are zero in every beat produced here.
//
// Pragmas are the Vitis HLS ones (PIPELINE, UNROLL, ARRAY_PARTITION, INLINE, ...), written as
// INTGRID_HLS_PRAGMA("HLS ..."), defined once for every kernel in hls/hls_pragma.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hls/fixed_int.hpp"
#include "hls/hls_pragma.hpp"

namespace intgrid::hls {

// The geometry of one beat of B-bit indices, LANES of them.
template <int B, int LANES>
struct IndexBeat {
  static_assert(B >= 4 && B <= 16, "index width B must be 4..16 bits");
  static_assert(LANES >= 1 && LANES <= 16, "LANES must be 1..16");
  static constexpr int kWidth = B * LANES;           // bits of the data bus
  static constexpr int kWords = (kWidth + 63) / 64;  // 64-bit words holding it
  static constexpr std::uint32_t kLaneMask = (std::uint32_t{1} << B) - 1u;
  // The largest index magnitude: 2^(B-1) - 1. -2^(B-1) is accepted as input and saturates.
  static constexpr std::int32_t kMaxIndex = (std::int32_t{1} << (B - 1)) - 1;
  using Words = std::array<std::uint64_t, kWords>;
};

template <int B, int LANES>
using Beat = typename IndexBeat<B, LANES>::Words;

// The B-bit two's-complement pattern of lane `lane` (bits [B-1:0] of the result, upper bits 0).
template <int B, int LANES>
constexpr std::uint32_t get_lane(const Beat<B, LANES>& beat, int lane) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  const int bit = lane * B;
  const int word = bit / 64;
  const int shift = bit % 64;
  std::uint64_t v = beat[static_cast<std::size_t>(word)] >> shift;
  // The lane straddles two words: its high bits come from the next one.
  if (shift + B > 64) v |= beat[static_cast<std::size_t>(word) + 1u] << (64 - shift);
  return static_cast<std::uint32_t>(v) & IndexBeat<B, LANES>::kLaneMask;
}

// Writes the low B bits of `value` into lane `lane`, leaving the other lanes unchanged.
template <int B, int LANES>
constexpr void set_lane(Beat<B, LANES>& beat, int lane, std::uint32_t value) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  const std::uint64_t v = value & IndexBeat<B, LANES>::kLaneMask;
  const std::uint64_t mask = IndexBeat<B, LANES>::kLaneMask;
  const int bit = lane * B;
  const auto word = static_cast<std::size_t>(bit / 64);
  const int shift = bit % 64;
  beat[word] = (beat[word] & ~(mask << shift)) | (v << shift);
  if (shift + B > 64) {
    const int low_bits = 64 - shift;  // bits of the lane that went into `word`
    beat[word + 1u] = (beat[word + 1u] & ~(mask >> low_bits)) | (v >> low_bits);
  }
}

// Sign extension of a B-bit pattern.
template <int B>
constexpr std::int32_t sign_extend(std::uint32_t pattern) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  const std::uint32_t sign = std::uint32_t{1} << (B - 1);
  const std::uint32_t low = pattern & ((std::uint32_t{1} << B) - 1u);
  return static_cast<std::int32_t>(low ^ sign) - static_cast<std::int32_t>(sign);
}

// One lane: the saturating adder of rtl/saturating_add.sv. a and b are B-bit patterns; the
// (B+1)-bit sum is clamped to +-(2^(B-1) - 1) and returned as a B-bit pattern.
template <int B>
constexpr std::uint32_t saturating_add(std::uint32_t a, std::uint32_t b) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  constexpr sint<B> kMax = (std::int32_t{1} << (B - 1)) - 1;
  const sint<B + 1> sum = sint<B>(sign_extend<B>(a)) + sint<B>(sign_extend<B>(b));
  const bool overflow_pos = sum > kMax;   // above +(2^(B-1) - 1)
  const bool overflow_neg = sum < -kMax;  // below -(2^(B-1) - 1), -2^(B-1) included
  const sint<B> y = overflow_pos ? kMax : (overflow_neg ? sint<B>(-kMax) : sint<B>(sum));
  return static_cast<std::uint32_t>(y.value()) & ((std::uint32_t{1} << B) - 1u);
}

// One beat: LANES saturating adders side by side (the combinational data path of the RTL).
template <int B, int LANES>
constexpr Beat<B, LANES> fuse_beat(const Beat<B, LANES>& a, const Beat<B, LANES>& b) {
  INTGRID_HLS_PRAGMA("HLS INLINE")
  Beat<B, LANES> y{};
  for (int lane = 0; lane < LANES; ++lane) {
    INTGRID_HLS_PRAGMA("HLS UNROLL")
    set_lane<B, LANES>(y, lane,
                       saturating_add<B>(get_lane<B, LANES>(a, lane), get_lane<B, LANES>(b, lane)));
  }
  return y;
}

// A top-level function for an HLS tool: N beats of two streams fused one beat per cycle.
// (The SystemC model in systemc/index_fusion_module.hpp adds the ready/valid protocol.)
template <int B, int LANES, std::size_t N>
void fuse_block(const std::array<Beat<B, LANES>, N>& a, const std::array<Beat<B, LANES>, N>& b,
                std::array<Beat<B, LANES>, N>& y) {
  // The words of a beat side by side, so a whole beat (up to 256 bits) moves in one cycle.
  INTGRID_HLS_PRAGMA("HLS ARRAY_PARTITION variable=a dim=2 complete")
  INTGRID_HLS_PRAGMA("HLS ARRAY_PARTITION variable=b dim=2 complete")
  INTGRID_HLS_PRAGMA("HLS ARRAY_PARTITION variable=y dim=2 complete")
  for (std::size_t i = 0; i < N; ++i) {
    INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
    y[i] = fuse_beat<B, LANES>(a[i], b[i]);
  }
}

// The accumulate variant: a grid tile of DEPTH beats (DEPTH * LANES cells) held in on-chip memory,
// into which whole tiles of observations are fused in raster order, one beat per cycle. Each
// address is read and written once per call, so the read-modify-write has no loop-carried
// dependence (DEPENDENCE inter false) and pipelines at II = 1 on a two-port RAM.
template <int B, int LANES, std::size_t DEPTH>
class FusionTile {
 public:
  using BeatT = Beat<B, LANES>;

  // tile[i] = sat(tile[i] + in[i]) for every beat i of the tile.
  void accumulate(const std::array<BeatT, DEPTH>& in) {
    INTGRID_HLS_PRAGMA("HLS BIND_STORAGE variable=tile_ type=ram_2p")
    // One RAM bank per 64-bit word of a beat: a whole beat is read and written per cycle.
    INTGRID_HLS_PRAGMA("HLS ARRAY_PARTITION variable=tile_ dim=2 complete")
    for (std::size_t i = 0; i < DEPTH; ++i) {
      INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
      INTGRID_HLS_PRAGMA("HLS DEPENDENCE variable=tile_ inter false")
      tile_[i] = fuse_beat<B, LANES>(tile_[i], in[i]);
    }
  }
  // Streams the tile out (e.g. to a map writer) in raster order.
  void read(std::array<BeatT, DEPTH>& out) const {
    for (std::size_t i = 0; i < DEPTH; ++i) {
      INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
      out[i] = tile_[i];
    }
  }
  // Back to "no information" (index 0, p = 1/2) everywhere.
  void clear() {
    for (std::size_t i = 0; i < DEPTH; ++i) {
      INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
      tile_[i] = BeatT{};
    }
  }

 private:
  std::array<BeatT, DEPTH> tile_{};
};

}  // namespace intgrid::hls
