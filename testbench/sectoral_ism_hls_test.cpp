// The synthesizable sectoral ISM (hls/sectoral_ism.hpp) against golden's bit-accurate integer
// model, for both hardware configurations: the generated tables equal golden's, the kernel
// equals ism_kernel_indices for every reading the 16-bit port holds, each operation equals
// golden's, and the RTL's word widths hold every value golden forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "hls/sectoral_ism.hpp"
#include "intgrid/kernel/hardware_configs.hpp"
#include "intgrid/kernel/ism_kernel.hpp"
#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"
#include "testbench/sectoral_ism_hls_synth.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;

namespace intgrid::hw {
namespace {

template <class Config>
class SectoralIsmHls : public ::testing::Test {
 protected:
  static const IsmKernelTables& kernel() {
    static const IsmKernelTables k = make_ism_hw_kernel(ism_hw_config(Config::name));
    return k;
  }
};
using Configs = ::testing::Types<SectoralIsmCone16, SectoralIsmCone12>;
TYPED_TEST_SUITE(SectoralIsmHls, Configs);

template <class A, class B>
bool same(const A& a, const B& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

TYPED_TEST(SectoralIsmHls, GeneratedTablesAreGoldens) {
  using C = TypeParam;
  const IsmKernelTables& k = this->kernel();
  EXPECT_EQ(C::rings, k.grid.rings);
  EXPECT_EQ(C::bins, k.grid.bins);
  EXPECT_EQ(C::sectors, k.grid.sectors);
  EXPECT_EQ(C::classes, k.classes);
  EXPECT_EQ(C::conditions, k.conditions);
  EXPECT_EQ(C::window_cells, k.window_cells);
  EXPECT_EQ(C::reach, k.reach);
  EXPECT_EQ(C::max_index, k.max_index);
  EXPECT_EQ(C::log_zero, IsmKernelTables::kLogZero);
  EXPECT_TRUE(same(C::quad_coef, k.quad_coef));
  EXPECT_TRUE(same(C::log_norm, k.log_norm));
  EXPECT_TRUE(same(C::log_weight, k.log_weight));
  EXPECT_TRUE(same(C::log_add, k.log_add));
  EXPECT_TRUE(same(C::thresholds, k.thresholds));
  const IsmHwDerived d = derive_ism_hw(k, C::index_bits);
  EXPECT_EQ(C::log_bits, d.log_bits);
  EXPECT_EQ(C::mul_digits, d.mul_digits);
  EXPECT_TRUE(same(C::threshold_bucket, threshold_buckets(k, d)));
  // The table widths hls/ derives itself are golden's.
  using W = hls::IsmWidths<C>;
  EXPECT_EQ(W::norm_bits, d.norm_bits);
  EXPECT_EQ(W::weight_bits, d.weight_bits);
  EXPECT_EQ(W::phi_bits, d.phi_bits);
  EXPECT_EQ(W::phi_count, static_cast<int>(k.log_add.size()));
  EXPECT_EQ(W::thr_bits, d.thr_bits);
  EXPECT_EQ(W::bucket_bits, d.bucket_bits);
}

TYPED_TEST(SectoralIsmHls, EveryReadingOfThePortIsGoldens) {
  using C = TypeParam;
  const IsmKernelTables& k = this->kernel();
  static std::int16_t out[C::rings * C::bins];
  std::vector<std::int16_t> want(k.grid.cells());
  std::size_t bad = 0;
  for (std::uint32_t z = 0; z < (1u << C::reading_bits); ++z) {
    hls::sectoral_ism_kernel<C>(z, out);
    ism_kernel_indices(k, z, want);
    if (!std::equal(want.begin(), want.end(), out)) {
      if (++bad <= 3) ADD_FAILURE() << C::name << ": reading " << z << " differs from golden";
    }
  }
  EXPECT_EQ(bad, 0u);
}

// The top functions (compiled with __SYNTHESIS__, 8-bit cells at the port) against golden for
// every reading in the sensor's reach and a stretch beyond it.
template <class C, class Top>
void check_top(const IsmKernelTables& k, Top top) {
  static std::int8_t cells[C::rings * C::bins];
  std::vector<std::int16_t> want(k.grid.cells());
  std::size_t bad = 0;
  for (std::uint32_t z = 0; z <= k.reach + 512; ++z) {
    const std::uint16_t reading[1] = {static_cast<std::uint16_t>(z)};
    top(reading, cells);
    ism_kernel_indices(k, z, want);
    if (!std::equal(want.begin(), want.end(), cells)) {
      if (++bad <= 3) ADD_FAILURE() << C::name << ": top function, reading " << z;
    }
  }
  EXPECT_EQ(bad, 0u);
}

TEST(SectoralIsmHlsTop, Cone16IsGoldens) {
  check_top<SectoralIsmCone16>(make_ism_hw_kernel(ism_hw_config("cone16")),
                               hls_synth::sectoral_ism_cone16);
}
TEST(SectoralIsmHlsTop, Cone12IsGoldens) {
  check_top<SectoralIsmCone12>(make_ism_hw_kernel(ism_hw_config("cone12")),
                               hls_synth::sectoral_ism_cone12);
}

// On the kernel's domain: finite log values within +-log_bound (RtlWordWidthsHoldEveryValue
// shows every value of the recursion lies there), products whose sum does too.
TYPED_TEST(SectoralIsmHls, LogAdditionAndProductAreGoldens) {
  using C = TypeParam;
  const IsmKernelTables& k = this->kernel();
  constexpr std::int32_t bound = C::log_bound;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int32_t> any(-bound, bound);
  std::uniform_int_distribution<std::int32_t> near(-3000, 3000);
  for (int i = 0; i < 200000; ++i) {
    std::int32_t a = any(rng);
    std::int32_t b = (i % 2) ? std::clamp(a + near(rng), -bound, bound) : any(rng);
    if (i % 97 == 0) a = C::log_zero;
    if (i % 89 == 0) b = C::log_zero;
    ASSERT_EQ((hls::ism_log_add<C>(a, b)), kernel_log_add(k, a, b)) << a << " " << b;
    // A product's factors: b drawn so that a + b stays within the bound.
    if (a != C::log_zero && b != C::log_zero)
      b = std::uniform_int_distribution<std::int32_t>(std::max(-bound, -bound - a),
                                                      std::min(bound, bound - a))(rng);
    ASSERT_EQ((hls::ism_log_mul<C>(a, b)), kernel_log_mul(a, b)) << a << " " << b;
  }
}

// The bucket table finds golden's count of thresholds for every magnitude, both signs.
TYPED_TEST(SectoralIsmHls, IndexOfEveryLogOddsIsGoldens) {
  using C = TypeParam;
  const IsmKernelTables& k = this->kernel();
  const std::int32_t top = C::thresholds.back() + (4 << C::bucket_shift);
  for (std::int32_t m = 0; m <= top; ++m) {
    ASSERT_EQ((hls::ism_index_of_log_odds<C>(m - 5000, -5000)),
              kernel_index_of_log_odds(k, m - 5000, -5000));
    ASSERT_EQ((hls::ism_index_of_log_odds<C>(-5000, m - 5000)),
              kernel_index_of_log_odds(k, -5000, m - 5000));
  }
  for (const std::int32_t x : {std::int32_t{0}, std::int32_t{-7}, std::int32_t{123456}}) {
    EXPECT_EQ((hls::ism_index_of_log_odds<C>(C::log_zero, x)), -C::max_index);
    EXPECT_EQ((hls::ism_index_of_log_odds<C>(x, C::log_zero)), C::max_index);
  }
  EXPECT_EQ((hls::ism_index_of_log_odds<C>(C::log_zero, C::log_zero)), 0);
}

// Golden's ring recursion with an arithmetic that records every finite value: all lie within
// +-log_bound, which the RTL's LOG_W-bit words hold (their differences in LOG_W + 1 bits).
template <class C>
struct RangeArith {
  const IsmKernelTables& k;
  std::uint32_t reading;
  std::int64_t* extreme;
  std::int32_t note(std::int32_t v) const {
    if (v != C::log_zero) *extreme = std::max<std::int64_t>(*extreme, v < 0 ? -std::int64_t{v} : v);
    return v;
  }
  std::int32_t zero() const { return C::log_zero; }
  std::int32_t add(std::int32_t a, std::int32_t b) const {
    return note(kernel_log_add(k, note(a), note(b)));
  }
  std::int32_t mul(std::int32_t a, std::int32_t b) const {
    return note(kernel_log_mul(note(a), note(b)));
  }
  std::int32_t log_density(int ring, std::size_t c) const {
    return note(hls::ism_log_density<C>(reading, ring, static_cast<int>(c)));
  }
  std::int32_t log_weight(int v, std::size_t c) const {
    return k.log_weight[std::size_t(v) * std::size_t(k.classes) + c];
  }
  std::int32_t ring_prior(int ring) const {
    return static_cast<std::int32_t>(
        -((std::int64_t{ring} - 1) * k.grid.bins << k.format.log_frac_bits));
  }
  std::int32_t two() const { return std::int32_t{1} << k.format.log_frac_bits; }
  int output(std::int32_t num, std::int32_t den) const {
    if (num != C::log_zero && den != C::log_zero) {
      const std::int64_t odds = std::int64_t{num} - den;
      *extreme = std::max<std::int64_t>(*extreme, (odds < 0 ? -odds : odds) / 2);
    }
    return kernel_index_of_log_odds(k, note(num), note(den));
  }
};

TYPED_TEST(SectoralIsmHls, RtlWordWidthsHoldEveryValue) {
  using C = TypeParam;
  const IsmKernelTables& k = this->kernel();
  std::int64_t extreme = 0;
  for (std::uint32_t z = 0; z <= k.reach; ++z) {
    const RangeArith<C> arith{k, z, &extreme};
    sectoral_ism_rings(arith, k.grid.rings, k.grid.sectors, std::size_t(k.classes),
                       [](int, int, int) {});
  }
  std::printf("%s: largest |log value| %lld, bound %d, LOG_W %d\n", C::name,
              static_cast<long long>(extreme), C::log_bound, C::log_bits);
  EXPECT_LE(extreme, C::log_bound);
  EXPECT_LT(std::int64_t{C::log_bound}, std::int64_t{1} << (C::log_bits - 1));
}

}  // namespace
}  // namespace intgrid::hw
