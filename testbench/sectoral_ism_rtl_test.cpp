// The sectoral ISM RTL (rtl/sectoral_ism.sv), Verilated once per configuration, against
// golden's ism_kernel_indices (testbench/sectoral_ism_rtl_bench.hpp checks every beat, the
// last flags, drops and duplicates, and output stability under back-pressure):
//   - edge readings plus 10,000 random ones with random input gaps and back-pressure;
//   - every reading the 16-bit port holds, in a shuffled order;
//   - heavy back-pressure;
//   - set-up cycles and latency as the schedule documents them (sectoral_ism_timing.hpp);
//   - full throughput: one cell per cycle, set-up hidden behind the other bank's output;
//   - a deliberately broken RTL (Phi read at d + 1) that the checker must catch.
// Randomized runs print their seed; INTGRID_ISM_SEED replays one. INTGRID_ISM_TRACE=DIR dumps
// DIR/<test>.vcd of each run on a shortened stimulus (about 24 readings).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "Vsectoral_ism_cone12.h"
#include "Vsectoral_ism_cone16.h"
#include "Vsectoral_ism_cone16_bug.h"
#include "intgrid/kernel/hardware_configs.hpp"
#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"
#include "systemc/sectoral_ism_timing.hpp"
#include "testbench/sectoral_ism_rtl_bench.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;

namespace intgrid::hw {
namespace {

const IsmKernelTables& kernel_of(const char* name) {
  static const IsmKernelTables cone16 = make_ism_hw_kernel(ism_hw_config("cone16"));
  static const IsmKernelTables cone12 = make_ism_hw_kernel(ism_hw_config("cone12"));
  return std::string(name) == "cone16" ? cone16 : cone12;
}

std::string trace_path() {
  const char* dir = std::getenv("INTGRID_ISM_TRACE");
  if (!dir || !*dir) return {};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string(dir) + "/" + info->test_suite_name() + "." + info->name() + ".vcd";
}

// The edges plus `random` readings. When tracing, about 24: the first 12 and the last 7 edges
// (below and on the first rings; the last ring, reach and past it) and 5 random ones.
std::vector<std::uint32_t> stimulus(const IsmKernelTables& k, std::size_t random,
                                    std::uint64_t seed) {
  std::vector<std::uint32_t> z = ism_edge_readings(k, kIsmReadingBits);
  if (!trace_path().empty()) {
    z.erase(z.begin() + 12, z.end() - 7);
    random = std::min<std::size_t>(random, 5);
  }
  const std::vector<std::uint32_t> r = ism_random_readings(k, kIsmReadingBits, random, seed);
  z.insert(z.end(), r.begin(), r.end());
  return z;
}

template <class Model, class Config>
void random_run(std::uint64_t default_seed) {
  const IsmKernelTables& k = kernel_of(Config::name);
  const std::uint64_t seed = ism_bench_seed(default_seed, Config::name);
  std::mt19937_64 rng(seed);
  IsmRtlBench<Model> bench(k, trace_path());
  // Three phases: light, medium and heavy back-pressure and gaps, all randomized.
  const std::vector<std::uint32_t> z = stimulus(k, 10000, seed);
  const std::size_t third = z.size() / 3;
  const double ready[3] = {0.9, 0.6, 0.35}, gap[3] = {0.05, 0.3, 0.6};
  std::size_t readings = 0, cells = 0;
  for (int phase = 0; phase < 3; ++phase) {
    IsmBenchOptions opt;
    opt.seed = rng();
    opt.ready = ready[phase];
    opt.gap = gap[phase];
    const auto first = z.begin() + static_cast<std::ptrdiff_t>(phase * third);
    const auto last = phase == 2 ? z.end() : first + static_cast<std::ptrdiff_t>(third);
    const std::vector<std::uint32_t> part(first, last);
    const IsmBenchResult r = bench.run(part, opt);
    EXPECT_TRUE(r.ok()) << Config::name << " phase " << phase << ": " << r.summary();
    EXPECT_EQ(r.readings, part.size());
    EXPECT_EQ(r.cells, part.size() * k.grid.cells());
    readings += r.readings;
    cells += r.cells;
  }
  std::printf("[%s] %zu readings, %zu cells checked against golden\n", Config::name, readings,
              cells);
}

TEST(SectoralIsmRtl, Cone16RandomReadingsWithGapsAndBackPressure) {
  random_run<Vsectoral_ism_cone16, SectoralIsmCone16>(16);
}
TEST(SectoralIsmRtl, Cone12RandomReadingsWithGapsAndBackPressure) {
  random_run<Vsectoral_ism_cone12, SectoralIsmCone12>(12);
}

// All 2^16 readings, shuffled, light random back-pressure and gaps.
template <class Model, class Config>
void every_reading() {
  const IsmKernelTables& k = kernel_of(Config::name);
  std::vector<std::uint32_t> z(std::size_t{1} << kIsmReadingBits);
  std::iota(z.begin(), z.end(), 0u);
  const std::uint64_t seed = ism_bench_seed(7, Config::name);
  std::shuffle(z.begin(), z.end(), std::mt19937_64(seed));
  if (!trace_path().empty()) z.resize(24);
  IsmRtlBench<Model> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.seed = seed;
  opt.ready = 0.95;
  opt.gap = 0.02;
  const IsmBenchResult r = bench.run(z, opt);
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.readings, z.size());
  std::printf("[%s] every reading: %s\n", Config::name, r.summary().c_str());
}

TEST(SectoralIsmRtl, Cone16EveryReadingOfThePort) {
  every_reading<Vsectoral_ism_cone16, SectoralIsmCone16>();
}
TEST(SectoralIsmRtl, Cone12EveryReadingOfThePort) {
  every_reading<Vsectoral_ism_cone12, SectoralIsmCone12>();
}

TEST(SectoralIsmRtl, Cone16HeavyBackPressureKeepsOutputsStable) {
  const IsmKernelTables& k = kernel_of("cone16");
  IsmRtlBench<Vsectoral_ism_cone16> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.seed = ism_bench_seed(3, "cone16 heavy back-pressure");
  opt.ready = 0.1;
  opt.gap = 0.9;
  const IsmBenchResult r = bench.run(stimulus(k, 30, opt.seed), opt);
  EXPECT_TRUE(r.ok()) << r.summary();
}

// Isolated readings (the kernel idle before each): the set-up takes exactly the documented
// cycles, and the first cell follows 3 cycles later.
template <class Model, class Config>
void schedule() {
  const IsmKernelTables& k = kernel_of(Config::name);
  IsmRtlBench<Model> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.isolated = true;
  opt.ready = 1.0;
  opt.gap = 0.0;
  std::vector<std::uint32_t> z = ism_edge_readings(k, kIsmReadingBits);
  const std::vector<std::uint32_t> r = ism_random_readings(k, kIsmReadingBits, 50, 99);
  z.insert(z.end(), r.begin(), r.end());
  const IsmBenchResult res = bench.run(z, opt);
  ASSERT_TRUE(res.ok()) << res.summary();
  ASSERT_EQ(res.setup_cycles.size(), z.size());
  ASSERT_EQ(res.latencies.size(), z.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    const std::uint64_t want = sc::sectoral_ism_setup_cycles<Config>(z[i]);
    EXPECT_EQ(res.setup_cycles[i], want) << "reading " << z[i];
    EXPECT_EQ(res.latencies[i], want + sc::kSectoralIsmStreamLatency) << "reading " << z[i];
  }
}

TEST(SectoralIsmRtl, Cone16SetupCyclesFollowTheSchedule) {
  schedule<Vsectoral_ism_cone16, SectoralIsmCone16>();
}
TEST(SectoralIsmRtl, Cone12SetupCyclesFollowTheSchedule) {
  schedule<Vsectoral_ism_cone12, SectoralIsmCone12>();
}

// Back-to-back readings, no back-pressure: with empty windows (z >= reach, 2 set-up cycles)
// the output never pauses; with full windows the kernel takes one reading per set-up (+ 1
// cycle to accept the next), the other bank's output hidden behind it.
template <class Model, class Config>
void throughput() {
  const IsmKernelTables& k = kernel_of(Config::name);
  IsmRtlBench<Model> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.ready = 1.0;
  opt.gap = 0.0;
  const std::size_t cells = k.grid.cells();
  std::vector<std::uint32_t> beyond(50);
  for (std::size_t i = 0; i < beyond.size(); ++i) beyond[i] = k.reach + std::uint32_t(i) * 37;
  const IsmBenchResult a = bench.run(beyond, opt);
  ASSERT_TRUE(a.ok()) << a.summary();
  EXPECT_LE(a.cycles, beyond.size() * cells + 16) << "the output paused";
  std::vector<std::uint32_t> inside(50);
  std::uint64_t bound = cells + 16;
  for (std::size_t i = 0; i < inside.size(); ++i) {
    inside[i] = std::uint32_t(i * 977) % k.reach;
    bound += std::max<std::uint64_t>(sc::sectoral_ism_setup_cycles<Config>(inside[i]) + 1, cells);
  }
  const IsmBenchResult b = bench.run(inside, opt);
  ASSERT_TRUE(b.ok()) << b.summary();
  EXPECT_LE(b.cycles, bound);
}

TEST(SectoralIsmRtl, Cone16FullThroughput) {
  throughput<Vsectoral_ism_cone16, SectoralIsmCone16>();
}
TEST(SectoralIsmRtl, Cone12FullThroughput) {
  throughput<Vsectoral_ism_cone12, SectoralIsmCone12>();
}

// The broken variant (SECTORAL_ISM_BUG_PHI: the log-add reads Phi(d + 1)) must fail the
// same checks that pass on the intact RTL.
TEST(SectoralIsmRtl, BrokenVariantIsCaught) {
  const IsmKernelTables& k = kernel_of("cone16");
  IsmRtlBench<Vsectoral_ism_cone16_bug> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.seed = ism_bench_seed(5, "cone16 broken");
  const IsmBenchResult r = bench.run(stimulus(k, 200, opt.seed), opt);
  EXPECT_GT(r.mismatches, 0u) << "the checker missed the broken Phi address";
  std::printf("[cone16 broken] caught: %s\n", r.summary().c_str());
}

}  // namespace
}  // namespace intgrid::hw
