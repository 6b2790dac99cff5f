// The bit-accurate integer ISM kernel against the double-precision sectoral ISM, and its
// arithmetic, one operation at a time, against double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/kernel/ism_kernel.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;

namespace intgrid {
namespace {

// Random readings over the grid and one cell past it, plus the edges: zero, below the
// first ring, on every ring, between rings, at and past the last ring.
std::vector<std::uint32_t> readings_for(const IsmKernelTables& k, int random, unsigned seed) {
  const std::uint32_t unit = 1u << k.format.reading_frac_bits;
  std::vector<std::uint32_t> out{0, 1, unit / 2, unit - 1};
  for (int r = 1; r <= k.grid.rings; ++r) {
    out.push_back(std::uint32_t(r) * unit);
    out.push_back(std::uint32_t(r) * unit + unit / 2);
  }
  out.push_back(std::uint32_t(k.grid.rings + 1) * unit);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::uint32_t> any(0, std::uint32_t(k.grid.rings + 1) * unit);
  for (int i = 0; i < random; ++i) out.push_back(any(rng));
  return out;
}

struct Case {
  const char* name;
  ConeSensorModel model;
  SectoralGrid grid;
  int bits;
  double eps;
};

const Case kCases[] = {
    {"default cone, 8-bit", ConeSensorModel{}, SectoralGrid{}, 8, 0.05},
    {"wide cone, 16 sectors", ConeSensorModel{0.03, 0.1, 1.0, 1.0},
     SectoralGrid{1.0, 60, 32, 16, 0.04}, 8, 0.02},
    {"narrow cone, 6-bit coarse", ConeSensorModel{0.05, 0.0, 0.3, 0.2},
     SectoralGrid{0.3, 25, 12, 3, 0.1}, 6, 0.2},
    {"one bin, 12-bit fine", ConeSensorModel{0.02, 0.05, 0.5, 0.5},
     SectoralGrid{0.05, 80, 1, 1, 0.025}, 12, 0.01},
};

TEST(IsmKernel, EveryIndexWithinOneStepOfTheQuantizedDoubleIsm) {
  for (const Case& c : kCases) {
    const SepsCodec codec(c.bits, c.eps);
    const IsmKernelTables kernel = make_ism_kernel(c.model, c.grid, codec);
    const std::vector<std::uint32_t> readings = readings_for(kernel, 2000, 7);
    const KernelAgreement a = measure_kernel_agreement(c.model, kernel, codec, readings);
    EXPECT_EQ(a.more, 0u) << c.name << ": worst step " << a.worst_step;
    EXPECT_EQ(a.cells, readings.size() * c.grid.cells());
    std::printf("%s: %zu readings, %zu cells, %.4f%% equal, %zu one step off\n", c.name, a.readings,
                a.cells, 100.0 * a.equal_share(), a.one_step);
    ::testing::Test::RecordProperty(c.name, std::to_string(a.equal_share()));
  }
}

TEST(IsmKernel, EveryReadingOfASmallGrid) {
  const ConeSensorModel model;
  const SectoralGrid grid{0.6, 6, 4, 2, 0.05};
  const SepsCodec codec(8, 0.05);
  const IsmKernelTables kernel = make_ism_kernel(model, grid, codec);
  std::vector<std::uint32_t> all;
  for (std::uint32_t z = 0; z <= std::uint32_t(grid.rings + 1) << 8; ++z) all.push_back(z);
  EXPECT_EQ(measure_kernel_agreement(model, kernel, codec, all).more, 0u);
}

TEST(IsmKernel, OneBinFollowsTheNarrowIsm) {
  const SectoralGrid grid{0.05, 50, 1, 1, 0.05};
  const SepsCodec codec(8, 0.05);
  const IsmKernelTables kernel = make_ism_kernel(ConeSensorModel{0.03, 0.0, 0.5, 0.5}, grid, codec);
  for (std::uint32_t z = 0; z < 51u << 8; z += 37) {
    const std::vector<double> p =
        narrow_ism(GaussianBeamModel{0.03, 0.0}, reading_metres(kernel, z), grid.cell, 50);
    const std::vector<std::int16_t> n = ism_kernel_indices(kernel, z);
    for (std::size_t i = 0; i < p.size(); ++i)
      ASSERT_LE(std::abs(n[i] - codec.quantize_conservative(p[i])), 1) << z << " " << i;
  }
}

TEST(IsmKernel, ReadingsPastTheReachInformNoCell) {
  const SepsCodec codec(8, 0.05);
  const IsmKernelTables kernel = make_ism_kernel(ConeSensorModel{}, SectoralGrid{}, codec);
  for (const std::uint32_t z : {kernel.reach, kernel.reach + 1, kernel.reach * 3})
    for (const std::int16_t n : ism_kernel_indices(kernel, z)) ASSERT_EQ(n, 0);
  // One unit short of the reach, the last ring still hears it.
  const std::vector<std::int16_t> last = ism_kernel_indices(kernel, kernel.reach - 1);
  EXPECT_NE(std::count(last.begin(), last.end(), 0), std::ptrdiff_t(last.size()));
}

TEST(IsmKernel, LogAddIsTheRoundedLogOfASum) {
  const SepsCodec codec(8, 0.05);
  const IsmKernelTables k = make_ism_kernel(ConeSensorModel{}, SectoralGrid{}, codec);
  const double one = std::exp2(k.format.log_frac_bits);
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::int32_t> value(-100'000, 100'000);
  for (int i = 0; i < 100'000; ++i) {
    const std::int32_t a = value(rng), b = a + value(rng) % 4000;
    const double exact = std::log2(std::exp2(a / one) + std::exp2(b / one)) * one;
    // One rounding of the table entry: within half a quantum, plus the table's cut-off.
    ASSERT_LE(std::abs(kernel_log_add(k, a, b) - exact), 0.5 + 1e-9) << a << " " << b;
    ASSERT_EQ(kernel_log_add(k, a, b), kernel_log_add(k, b, a));
  }
  const std::int32_t zero = IsmKernelTables::kLogZero;
  EXPECT_EQ(kernel_log_add(k, zero, 123), 123);
  EXPECT_EQ(kernel_log_add(k, zero, zero), zero);
  EXPECT_EQ(kernel_log_mul(zero, 5), zero);
  EXPECT_EQ(kernel_log_mul(-(1 << 29), -(1 << 29)), zero);
  EXPECT_EQ(kernel_log_mul(-7, 12), 5);
}

TEST(IsmKernel, ThresholdsGiveTheConservativeIndexOfTheOdds) {
  for (const auto& [bits, eps] : {std::pair{8, 0.05}, std::pair{4, 0.3}, std::pair{16, 0.001}}) {
    const SepsCodec codec(bits, eps);
    const IsmKernelTables k = make_ism_kernel(ConeSensorModel{}, SectoralGrid{}, codec);
    const double one = std::exp2(k.format.log_frac_bits);
    std::mt19937 rng(5);
    std::uniform_int_distribution<std::int32_t> odds(-40 * int(one), 40 * int(one));
    for (int i = 0; i < 20'000; ++i) {
      const std::int32_t l = odds(rng);
      const double nats = l / one * std::numbers::ln2;
      // Oracle: truncate the odds in steps of lambda toward zero, in long double, away
      // from the thresholds themselves; and, where a double probability still resolves
      // the odds, the codec's own conservative quantization agrees.
      const long double steps = (long double)nats / codec.lambda();
      if (std::abs(steps - std::round(steps)) < 1e-9L) continue;
      const long double truncated = std::trunc(steps);
      const int expected =
          int(std::clamp<long double>(truncated, -codec.max_index(), codec.max_index()));
      ASSERT_EQ(kernel_index_of_log_odds(k, l, 0), expected) << bits << " " << l;
      if (std::abs(nats) < 15.0 && std::abs(steps - std::round(steps)) > 1e-3L) {
        ASSERT_EQ(expected, codec.quantize_conservative(logistic(nats))) << bits << " " << l;
      }
      ASSERT_EQ(kernel_index_of_log_odds(k, 1000 + l, 1000), kernel_index_of_log_odds(k, l, 0));
    }
    const std::int32_t zero = IsmKernelTables::kLogZero;
    EXPECT_EQ(kernel_index_of_log_odds(k, zero, 0), -codec.max_index());
    EXPECT_EQ(kernel_index_of_log_odds(k, 0, zero), codec.max_index());
    EXPECT_EQ(kernel_index_of_log_odds(k, zero, zero), 0);
  }
}

TEST(IsmKernel, RejectsWhatItCannotHold) {
  const SepsCodec codec(8, 0.05);
  EXPECT_THROW(make_ism_kernel(ConeSensorModel{}, SectoralGrid{0.5, 40, 32, 32, 0.05}, codec),
               std::invalid_argument);
  EXPECT_THROW(make_ism_kernel(ConeSensorModel{}, SectoralGrid{0.5, 40, 16, 3, 0.05}, codec),
               std::invalid_argument);
  EXPECT_THROW(make_ism_kernel(ConeSensorModel{-1.0}, SectoralGrid{}, codec),
               std::invalid_argument);
  // sigma of 40 cells: the window would pass 4096 cells.
  EXPECT_THROW(make_ism_kernel(ConeSensorModel{2.0, 0.0, 0.5, 0.5}, SectoralGrid{}, codec),
               std::invalid_argument);
  const IsmKernelTables k = make_ism_kernel(ConeSensorModel{}, SectoralGrid{}, codec);
  EXPECT_THROW(quantize_reading(k, std::nan("")), std::invalid_argument);
  EXPECT_THROW(quantize_reading(k, -0.01), std::invalid_argument);
  EXPECT_THROW(quantize_reading(k, 1e12), std::invalid_argument);
  EXPECT_EQ(quantize_reading(k, 1.0), 20u << 8);
  EXPECT_DOUBLE_EQ(reading_metres(k, 20u << 8), 1.0);
}

}  // namespace
}  // namespace intgrid
