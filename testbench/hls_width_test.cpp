// hls/ with width checking on (INTGRID_HLS_WIDTH_CHECK, set for this program only): every value
// stored into a declared width is logged (hls/fixed_int.hpp). Over every reading of the port
// no value of the sectoral ISM exceeds its declared width, and over every pair of indices none
// of index fusion's does; a configuration with one declared width a bit too narrow is caught
// (the checker is live and the widths are tight); the checker's own wrap and overflow
// decisions against built-in arithmetic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "hls/fixed_int.hpp"
#include "hls/index_fusion.hpp"
#include "hls/sectoral_ism.hpp"
#include "intgrid/core/seps.hpp"
#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"

#ifndef INTGRID_HLS_WIDTH_CHECK
#error "hls_width_test.cpp must be compiled with INTGRID_HLS_WIDTH_CHECK defined"
#endif

namespace intgrid::hw {
namespace {

namespace hls = intgrid::hls;

// ---- the checker itself ------------------------------------------------------------------------

// Wrapping into W bits against the built-in conversion to an exact-width type, and the overflow
// decision against the range test written out.
TEST(HlsWidthChecker, WrapsAndCountsLikeBuiltinConversions) {
  std::mt19937_64 rng(5);
  hls::width_log() = {};
  std::uint64_t expected_overflows = 0;
  for (int i = 0; i < 100000; ++i) {
    const auto x = static_cast<std::int64_t>(rng() >> (rng() % 60));
    const std::int64_t s = (i % 2) ? x : -x;
    const hls::sint<8> s8 = s;
    const hls::sint<16> s16 = s;
    const hls::uint<8> u8 = s;
    ASSERT_EQ(s8.value(), static_cast<std::int8_t>(s));
    ASSERT_EQ(s16.value(), static_cast<std::int16_t>(s));
    ASSERT_EQ(u8.value(), static_cast<std::uint8_t>(s));
    expected_overflows += (s < -128 || s > 127) + (s < -32768 || s > 32767) + (s < 0 || s > 255);
  }
  EXPECT_EQ(hls::width_log().overflows, expected_overflows);
  EXPECT_GT(expected_overflows, 0u);
  // The boundaries.
  hls::width_log() = {};
  hls::sint<5> in_range[] = {-16, 15};
  hls::uint<5> unsigned_in_range[] = {0, 31};
  EXPECT_EQ(hls::width_log().overflows, 0u);
  hls::sint<5> over = 16;
  hls::uint<5> under = -1;
  EXPECT_EQ(hls::width_log().overflows, 2u);
  EXPECT_EQ(over.value(), -16);
  EXPECT_EQ(under.value(), 31);
  EXPECT_EQ(in_range[0] + unsigned_in_range[1], 15);
}

// The operators' results are exact and of the widths the rules give.
TEST(HlsWidthChecker, ArithmeticIsExact) {
  std::mt19937_64 rng(6);
  std::uniform_int_distribution<std::int64_t> s12(-2048, 2047), u12(0, 4095);
  hls::width_log() = {};
  for (int i = 0; i < 100000; ++i) {
    const std::int64_t a = s12(rng), b = s12(rng), c = u12(rng);
    const hls::sint<12> x = a, y = b;
    const hls::uint<12> u = c;
    const auto sum = x + y;
    const auto difference = u - x;
    const auto product = x * u;
    static_assert(std::is_same_v<decltype(sum), const hls::sint<13>>);
    static_assert(std::is_same_v<decltype(difference), const hls::sint<14>>);
    static_assert(std::is_same_v<decltype(product), const hls::sint<25>>);
    ASSERT_EQ(sum.value(), a + b);
    ASSERT_EQ(difference.value(), c - a);
    ASSERT_EQ(product.value(), a * c);
    ASSERT_EQ(hls::shl<3>(x).value(), a * 8);
    ASSERT_EQ(hls::shr<3>(x).value(), a >= 0 ? a / 8 : -((-a + 7) / 8));  // floor
    ASSERT_EQ(hls::magnitude(x).value(), a < 0 ? -a : a);
    ASSERT_EQ(x < u, a < c);
  }
  EXPECT_EQ(hls::width_log().overflows, 0u);
}

// ---- the sectoral ISM ---------------------------------------------------------------------------

// Every reading the port holds, through the kernel with every store logged.
template <class Config>
hls::WidthLog run_every_reading(std::uint32_t last) {
  hls::width_log() = {};
  static std::int16_t out[Config::rings * Config::bins];
  for (std::uint32_t z = 0; z <= last; ++z) hls::sectoral_ism_kernel<Config>(z, out);
  return hls::width_log();
}

// The logged extremes of one declared width (0 unsigned, 1 signed), printed for the report.
void print_width(const char* config, const char* what, const hls::WidthLog& log, int s, int w) {
  std::printf("%s: %-34s %s<%2d>  seen %8lld .. %8lld  (%llu stores, %llu overflows)\n", config,
              what, s ? "sint" : "uint", w, static_cast<long long>(log.lowest[s][w]),
              static_cast<long long>(log.highest[s][w]),
              static_cast<unsigned long long>(log.stores_of[s][w]),
              static_cast<unsigned long long>(log.overflows_of[s][w]));
}

template <class Config>
class HlsWidthIsm : public ::testing::Test {};
using Configs = ::testing::Types<SectoralIsmCone16, SectoralIsmCone12>;
TYPED_TEST_SUITE(HlsWidthIsm, Configs);

TYPED_TEST(HlsWidthIsm, NoValueExceedsItsWidthOverEveryReading) {
  using C = TypeParam;
  using W = hls::IsmWidths<C>;
  const hls::WidthLog log = run_every_reading<C>((1u << C::reading_bits) - 1);
  print_width(C::name, "reading", log, 0, C::reading_bits);
  print_width(C::name, "ring number", log, 0, W::ring_bits);
  print_width(C::name, "|z - d_r| (E_W)", log, 0, C::e_bits);
  print_width(C::name, "(z - d_r)^2 (SQ_W)", log, 0, C::sq_bits);
  print_width(C::name, "quad_coef (COEF_W)", log, 0, C::coef_bits);
  print_width(C::name, "log_norm", log, 1, W::norm_bits);
  print_width(C::name, "log_weight", log, 1, W::weight_bits);
  print_width(C::name, "log values, quad (LOG_W)", log, 1, W::log_bits);
  print_width(C::name, "quad, distance (LOG_W, unsigned)", log, 0, W::log_bits);
  print_width(C::name, "Phi - 1", log, 0, W::phi_bits);
  print_width(C::name, "odds (LOG_W + 1)", log, 1, W::log_bits + 1);
  print_width(C::name, "|odds| (LOG_W + 1)", log, 0, W::log_bits + 1);
  print_width(C::name, "threshold", log, 0, W::thr_bits);
  print_width(C::name, "bucket count, n", log, 0, W::bucket_bits);
  print_width(C::name, "index", log, 1, C::index_bits);
  EXPECT_EQ(log.overflows, 0u);
  // The log saw the kernel's values at every width the kernel declares.
  EXPECT_GT(log.stores_of[0][C::e_bits], 0u);
  EXPECT_GT(log.stores_of[0][C::sq_bits], 0u);
  EXPECT_GT(log.stores_of[0][C::coef_bits], 0u);
  EXPECT_GT(log.stores_of[1][W::log_bits], 0u);
  EXPECT_GT(log.stores_of[1][W::log_bits + 1], 0u);
  EXPECT_GT(log.stores_of[0][W::thr_bits], 0u);
  EXPECT_GT(log.stores_of[1][C::index_bits], 0u);
  // The largest log value fits LOG_W with a sign, and needs all of it: LOG_W - 1 would not do.
  const std::int64_t largest = std::max(-log.lowest[1][W::log_bits], log.highest[1][W::log_bits]);
  EXPECT_LE(largest, C::log_bound);
  EXPECT_GT(largest, (std::int64_t{1} << (W::log_bits - 2)) - 1);
}

// A configuration with one width a bit narrower than declared.
template <class C>
struct NarrowLog : C {
  static constexpr int log_bits = C::log_bits - 1;
};
template <class C>
struct NarrowError : C {
  static constexpr int e_bits = C::e_bits - 1;
};
template <class C>
struct NarrowSquare : C {
  static constexpr int sq_bits = C::sq_bits - 1;
};
template <class C>
struct NarrowCoef : C {
  static constexpr int coef_bits = C::coef_bits - 1;
};

// Each narrowed width overflows somewhere in the sensor's reach: the checker sees it, and the
// declared width is the least that holds the kernel's values.
TYPED_TEST(HlsWidthIsm, OneBitNarrowerIsCaught) {
  using C = TypeParam;
  EXPECT_GT(run_every_reading<NarrowLog<C>>(C::reach).overflows, 0u);
  EXPECT_GT(run_every_reading<NarrowError<C>>(C::reach).overflows, 0u);
  EXPECT_GT(run_every_reading<NarrowSquare<C>>(C::reach).overflows, 0u);
  EXPECT_GT(run_every_reading<NarrowCoef<C>>(C::reach).overflows, 0u);
  // The declared widths themselves: none over the same readings.
  EXPECT_EQ(run_every_reading<C>(C::reach).overflows, 0u);
}

// ---- index fusion -------------------------------------------------------------------------------

// Every pair of B-bit indices through the saturating adder: the (B+1)-bit sum and the B-bit
// result never overflow, and the result is golden's.
template <int B>
void check_fusion_widths() {
  hls::width_log() = {};
  constexpr int kMin = -(1 << (B - 1)), kMax = (1 << (B - 1)) - 1;
  constexpr std::uint32_t kMask = (std::uint32_t{1} << B) - 1u;
  for (int a = kMin; a <= kMax; ++a)
    for (int b = kMin; b <= kMax; ++b) {
      const std::uint32_t y = hls::saturating_add<B>(static_cast<std::uint32_t>(a) & kMask,
                                                     static_cast<std::uint32_t>(b) & kMask);
      const int want = intgrid::core::fuse_indices<int>(a, b, kMax);
      ASSERT_EQ(y, static_cast<std::uint32_t>(want) & kMask) << a << " + " << b;
    }
  EXPECT_EQ(hls::width_log().overflows, 0u) << "B=" << B;
  EXPECT_GT(hls::width_log().stores_of[1][B + 1], 0u) << "B=" << B;  // the lane sums
  EXPECT_EQ(hls::width_log().lowest[1][B + 1], 2 * kMin) << "B=" << B;
  EXPECT_EQ(hls::width_log().highest[1][B + 1], 2 * kMax) << "B=" << B;
}

TEST(HlsWidthFusion, NoValueExceedsItsWidthForEveryPair) {
  check_fusion_widths<4>();
  check_fusion_widths<8>();
  check_fusion_widths<10>();
}

}  // namespace
}  // namespace intgrid::hw
