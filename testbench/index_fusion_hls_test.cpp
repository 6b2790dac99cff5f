// The HLS function of kernel 1 (hls/index_fusion.hpp) against golden intgrid::core::fuse_indices:
// every width B = 4..16 (exhaustive where 2^(2B) <= 2^20, 2^20 random pairs beyond), the packing
// of a beat against the bus packing the RTL testbench drives, and the accumulate variant. Part of
// it is compiled a second time with __SYNTHESIS__ defined (index_fusion_hls_synth.cpp) so that the
// HLS pragmas are expanded and shown not to change the C++ semantics.
#include "hls/index_fusion.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "intgrid/core/seps.hpp"
#include "testbench/index_fusion_hls_synth.hpp"
#include "testbench/index_fusion_tb.hpp"

using namespace intgrid::core;

namespace {

using intgrid::tb::sign_extend;
namespace hls = intgrid::hls;

// Compile-time spot checks (the functions are constexpr).
static_assert(hls::saturating_add<8>(0x7f, 0x01) == 0x7f);  // 127 + 1 -> 127
static_assert(hls::saturating_add<8>(0x80, 0x00) == 0x81);  // -128 + 0 -> -127
static_assert(hls::saturating_add<8>(0x80, 0x80) == 0x81);  // -128 + -128 -> -127
static_assert(hls::saturating_add<8>(0xff, 0x01) == 0x00);  // -1 + 1 -> 0
static_assert(hls::saturating_add<4>(0x9, 0xf) == 0x9);     // -7 + -1 -> -7
static_assert(hls::saturating_add<16>(0x7ffe, 0x0001) == 0x7fff);
static_assert(hls::IndexBeat<16, 16>::kWords == 4 && hls::IndexBeat<10, 7>::kWords == 2);

template <int B>
void check_width(std::mt19937_64& rng) {
  constexpr int kMin = -(1 << (B - 1)), kMax = (1 << (B - 1)) - 1;
  constexpr std::uint32_t kMask = (std::uint32_t{1} << B) - 1u;
  std::uint64_t mismatches = 0, checked = 0;
  auto check = [&](int a, int b) {
    const int got = sign_extend(hls::saturating_add<B>(static_cast<std::uint32_t>(a) & kMask,
                                                       static_cast<std::uint32_t>(b) & kMask),
                                B);
    const int want = intgrid::core::fuse_indices<int>(a, b, kMax);
    ++checked;
    if (got != want) {
      if (++mismatches <= 5)
        ADD_FAILURE() << "B=" << B << ": " << a << " + " << b << " -> " << got << ", golden "
                      << want;
    }
  };
  if (2 * B <= 20) {
    for (int a = kMin; a <= kMax; ++a)
      for (int b = kMin; b <= kMax; ++b) check(a, b);
    EXPECT_EQ(checked, std::uint64_t{1} << (2 * B));
  } else {
    std::uniform_int_distribution<int> index(kMin, kMax);
    for (int i = 0; i < (1 << 20); ++i) check(index(rng), index(rng));
    for (int a : {kMin, -kMax, -kMax + 1, -1, 0, 1, kMax - 1, kMax})
      for (int b : {kMin, -kMax, -kMax + 1, -1, 0, 1, kMax - 1, kMax}) check(a, b);
  }
  EXPECT_EQ(mismatches, 0u) << "B=" << B;
}

TEST(IndexFusionHls, SaturatingAddMatchesGoldenForEveryWidth) {
  std::mt19937_64 rng(intgrid::tb::test_seed("index_fusion_hls_widths"));
  [&]<int... I>(std::integer_sequence<int, I...>) {
    (check_width<I + 4>(rng), ...);
  }
  (std::make_integer_sequence<int, 13>{});
}

// A beat built lane by lane: lanes read back, the fused beat matches golden lane by lane, the bits
// above LANES*B stay zero, and the 64-bit words equal the bus the RTL testbench drives.
template <int B, int LANES>
void check_beat(std::mt19937_64& rng) {
  using Geometry = hls::IndexBeat<B, LANES>;
  constexpr int kMin = -(1 << (B - 1)), kMax = Geometry::kMaxIndex;
  std::uniform_int_distribution<int> index(kMin, kMax);
  for (int round = 0; round < 2000; ++round) {
    std::array<std::int32_t, LANES> a{}, b{};
    hls::Beat<B, LANES> beat_a{}, beat_b{};
    for (std::size_t l = 0; l < LANES; ++l) {
      a[l] = index(rng);
      b[l] = index(rng);
    }
    // Set the lanes in a scrambled order, twice, so a set_lane that disturbs a neighbour shows.
    for (int pass = 0; pass < 2; ++pass) {
      for (int i = 0; i < LANES; ++i) {
        const int l = (i * 17 + pass) % LANES;  // 17: coprime with every LANES
        const auto lane = static_cast<std::size_t>(l);
        hls::set_lane<B, LANES>(beat_a, l,
                                static_cast<std::uint32_t>(pass == 0 ? ~a[lane] : a[lane]));
        hls::set_lane<B, LANES>(beat_b, l, static_cast<std::uint32_t>(b[lane]));
      }
    }
    const intgrid::tb::Bits bus = intgrid::tb::pack_lanes<B, LANES>(a);
    for (std::size_t w = 0; w < Geometry::kWords; ++w)
      ASSERT_EQ(beat_a[w], (std::uint64_t{bus.w[2 * w + 1]} << 32) | bus.w[2 * w])
          << "B=" << B << " LANES=" << LANES << " word " << w;
    const hls::Beat<B, LANES> y = hls::fuse_beat<B, LANES>(beat_a, beat_b);
    for (int l = 0; l < LANES; ++l) {
      const auto lane = static_cast<std::size_t>(l);
      ASSERT_EQ(sign_extend(hls::get_lane<B, LANES>(beat_a, l), B), a[lane]);
      ASSERT_EQ(sign_extend(hls::get_lane<B, LANES>(y, l), B),
                intgrid::core::fuse_indices<int>(a[lane], b[lane], kMax))
          << "B=" << B << " LANES=" << LANES << " lane " << l;
    }
    if constexpr (Geometry::kWidth % 64 != 0) {
      ASSERT_EQ(y[Geometry::kWords - 1] >> (Geometry::kWidth % 64), 0u);
    }
  }
}

TEST(IndexFusionHls, FuseBeatPacksLikeTheRtlBus) {
  std::mt19937_64 rng(intgrid::tb::test_seed("index_fusion_hls_beats"));
  check_beat<4, 1>(rng);
  check_beat<4, 16>(rng);
  check_beat<5, 13>(rng);  // 65 bits
  check_beat<6, 16>(rng);  // lanes straddle 32- and 64-bit words
  check_beat<8, 8>(rng);
  check_beat<8, 16>(rng);
  check_beat<10, 7>(rng);  // 70 bits
  check_beat<12, 6>(rng);
  check_beat<12, 8>(rng);
  check_beat<16, 1>(rng);
  check_beat<16, 16>(rng);  // 256 bits
}

TEST(IndexFusionHls, FuseBlockFusesEveryBeat) {
  std::mt19937_64 rng(intgrid::tb::test_seed("index_fusion_hls_block"));
  constexpr std::size_t kN = 256;
  std::array<hls::Beat<12, 8>, kN> a{}, b{}, y{};
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t w = 0; w < a[i].size(); ++w) {
      a[i][w] = rng();
      b[i][w] = rng();
    }
  // Bits above 96 are junk here; only the lanes count.
  hls::fuse_block<12, 8, kN>(a, b, y);
  for (std::size_t i = 0; i < kN; ++i)
    for (int l = 0; l < 8; ++l)
      ASSERT_EQ(
          sign_extend(hls::get_lane<12, 8>(y[i], l), 12),
          intgrid::core::fuse_indices<int>(sign_extend(hls::get_lane<12, 8>(a[i], l), 12),
                                           sign_extend(hls::get_lane<12, 8>(b[i], l), 12), 2047));
}

// The accumulate variant: a tile fused with many random observation tiles equals golden's
// running saturating sum, cell by cell (long runs of same-sign observations drive the cells into
// saturation and back).
template <int B, int LANES, std::size_t DEPTH>
void check_tile(std::mt19937_64& rng) {
  constexpr int kMax = (1 << (B - 1)) - 1;
  hls::FusionTile<B, LANES, DEPTH> tile;
  tile.clear();
  std::vector<int> reference(DEPTH * LANES, 0);
  std::uniform_int_distribution<int> observation(-(1 << (B - 1)), kMax);
  for (int round = 0; round < 200; ++round) {
    std::array<hls::Beat<B, LANES>, DEPTH> in{};
    const int bias = (round / 20) % 2 == 0 ? kMax / 4 : -kMax / 4;
    for (std::size_t i = 0; i < DEPTH; ++i)
      for (int l = 0; l < LANES; ++l) {
        const int v = std::clamp(observation(rng) / 8 + bias, -(1 << (B - 1)), kMax);
        hls::set_lane<B, LANES>(in[i], l, static_cast<std::uint32_t>(v));
        int& ref = reference[i * LANES + static_cast<std::size_t>(l)];
        ref = intgrid::core::fuse_indices<int>(ref, v, kMax);
      }
    tile.accumulate(in);
  }
  std::array<hls::Beat<B, LANES>, DEPTH> out{};
  tile.read(out);
  for (std::size_t i = 0; i < DEPTH; ++i)
    for (int l = 0; l < LANES; ++l)
      ASSERT_EQ(sign_extend(hls::get_lane<B, LANES>(out[i], l), B),
                reference[i * LANES + static_cast<std::size_t>(l)])
          << "beat " << i << " lane " << l;
}

TEST(IndexFusionHls, AccumulateTileMatchesGoldenRunningSum) {
  std::mt19937_64 rng(intgrid::tb::test_seed("index_fusion_hls_tile"));
  check_tile<8, 8, 64>(rng);
  check_tile<12, 6, 32>(rng);
  check_tile<4, 16, 16>(rng);
}

// The same functions compiled with __SYNTHESIS__ (pragmas expanded) agree with these.
TEST(IndexFusionHls, SynthesisBuildAgrees) {
  for (std::uint32_t a = 0; a < 256; ++a)
    for (std::uint32_t b = 0; b < 256; ++b)
      ASSERT_EQ(intgrid::hls_synth::saturating_add_b8(a, b), hls::saturating_add<8>(a, b));
  std::mt19937_64 rng(1);
  for (int i = 0; i < 1000; ++i) {
    hls::Beat<12, 8> a{}, b{};
    for (auto& w : a) w = rng();
    for (auto& w : b) w = rng();
    ASSERT_EQ(intgrid::hls_synth::fuse_beat_b12_l8(a, b), (hls::fuse_beat<12, 8>(a, b)));
  }
  EXPECT_TRUE(intgrid::hls_synth::tile_b8_l8_self_check());
}

// The top function (compiled with __SYNTHESIS__) fuses every lane of a beat like golden.
TEST(IndexFusionHls, TopFunctionFusesLikeGolden) {
  std::mt19937_64 rng(intgrid::tb::test_seed("index_fusion_hls_top"));
  for (int i = 0; i < 20000; ++i) {
    const std::uint64_t a[1] = {rng()}, b[1] = {rng()};
    std::uint64_t y[1] = {};
    intgrid::hls_synth::index_fusion_b8_l8(a, b, y);
    for (int l = 0; l < 8; ++l) {
      const auto lane = [l](std::uint64_t w) {
        return sign_extend(static_cast<std::uint32_t>((w >> (8 * l)) & 0xffu), 8);
      };
      ASSERT_EQ(lane(y[0]), intgrid::core::fuse_indices<int>(lane(a[0]), lane(b[0]), 127))
          << "lane " << l;
    }
  }
}

}  // namespace
