// The sectoral ISM RTL (rtl/sectoral_ism.sv), Verilated once per configuration, against
// golden's ism_kernel_indices (testbench/sectoral_ism_rtl_bench.hpp checks every beat, the
// last flags, drops and duplicates, and output stability under back-pressure):
//   - edge readings plus 10,000 random ones with random input gaps and back-pressure;
//   - every reading the 16-bit port holds, in a shuffled order;
//   - heavy back-pressure;
//   - set-up cycles and latency as the schedule documents them (sectoral_ism_timing.hpp);
//   - full throughput: one cell per cycle, set-up hidden behind the other bank's output;
//   - a deliberately broken RTL (Phi read at d + 1) that the checker must catch;
//   - no wasted ready cycle (every run), the exact back-to-back schedule, and the bubble fault;
//   - z_ready low in reset; resets in the middle of a set-up and of an output, and random
//     initial states, each followed by a run equal, cycle for cycle, to one from power-up;
//   - the RTL's assertions live: each fires on a protocol violation or a fault-injected model.
// Randomized runs print their seed; INTGRID_ISM_SEED replays one. INTGRID_WAVES=DIR dumps
// DIR/<suite>.<test>.fst of each run on a shortened stimulus (about 24 readings); a failing
// test prints the command that does so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "Vsectoral_ism_cone12.h"
#include "Vsectoral_ism_cone12_ready.h"
#include "Vsectoral_ism_cone16.h"
#include "Vsectoral_ism_cone16_bubble.h"
#include "Vsectoral_ism_cone16_bug.h"
#include "Vsectoral_ism_stream_none.h"
#include "Vsectoral_ism_stream_spill_bubble.h"
#include "Vsectoral_ism_stream_spill_overwrite.h"
#include "Vsectoral_ism_stream_stream_bubble.h"
#include "Vsectoral_ism_stream_stream_last.h"
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

// DIR/<suite>.<test>.fst for the first bench of a test, .2.fst, .3.fst ... for the next ones.
std::string waves_path(const char* dir) {
  static std::string test;
  static int benches = 0;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = std::string(info->test_suite_name()) + "." + info->name();
  benches = name == test ? benches + 1 : 1;
  test = name;
  return std::string(dir) + "/" + name +
         (benches > 1 ? "." + std::to_string(benches) : std::string()) + ".fst";
}
bool waves_on() {
  const char* dir = std::getenv("INTGRID_WAVES");
  return dir && *dir;
}
std::string trace_path() {
  return waves_on() ? waves_path(std::getenv("INTGRID_WAVES")) : "";
}

// A failing test says how to see its waves (one test, one FST file).
class WavesHint : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& info) override {
    if (info.result()->Failed() && !waves_on())
      std::printf("[waves] INTGRID_WAVES=<dir> sectoral_ism_rtl_test --gtest_filter=%s.%s\n",
                  info.test_suite_name(), info.name());
  }
};
const bool g_waves_hint = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new WavesHint);
  return true;
}();

// The edges plus `random` readings. When tracing, about 24: the first 12 and the last 7 edges
// (below and on the first rings; the last ring, reach and past it) and 5 random ones.
std::vector<std::uint32_t> stimulus(const IsmKernelTables& k, std::size_t random,
                                    std::uint64_t seed) {
  std::vector<std::uint32_t> z = ism_edge_readings(k, kIsmReadingBits);
  if (waves_on()) {
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
    opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
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
  if (waves_on()) z.resize(24);
  IsmRtlBench<Model> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
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
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<SectoralIsmCone16>;
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
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
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
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
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

// The broken variant (log_add_phi: the log-add reads Phi(d + 1)) must fail the
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

// Back to back at full rate (no gaps, y_ready always high): the schedule predicts every accept
// and every first cell. Reading i is taken when the engine is idle (a[i-1] + s[i-1] + 1) and
// the bank of reading i - 2 is free (its last cell read, first[i-2] + cells - 2); its first cell
// leaves when its bank is written (a[i] + s[i] + 3) and the previous reading has gone. So y_valid
// is low between cells exactly sum(first[i] - first[i-1] - cells) cycles.
template <class Model, class Config>
void back_to_back_schedule() {
  const IsmKernelTables& k = kernel_of(Config::name);
  const std::uint64_t cells = k.grid.cells();
  std::vector<std::uint32_t> z = ism_edge_readings(k, kIsmReadingBits);
  const std::vector<std::uint32_t> r = ism_random_readings(k, kIsmReadingBits, 40, 31);
  z.insert(z.end(), r.begin(), r.end());
  IsmRtlBench<Model> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
  opt.ready = 1.0;
  opt.gap = 0.0;
  const IsmBenchResult res = bench.run(z, opt);
  ASSERT_TRUE(res.ok()) << res.summary();
  ASSERT_EQ(res.accept_cycles.size(), z.size());
  ASSERT_EQ(res.first_cells.size(), z.size());
  std::vector<std::uint64_t> accept(z.size()), first(z.size());
  std::uint64_t idle = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const auto setup = [&](std::size_t j) { return sc::sectoral_ism_setup_cycles<Config>(z[j]); };
    accept[i] = i == 0 ? 0 : accept[i - 1] + setup(i - 1) + 1;
    if (i >= 2) accept[i] = std::max(accept[i], first[i - 2] + cells - 2);
    first[i] = accept[i] + setup(i) + sc::kSectoralIsmStreamLatency;
    if (i >= 1) {
      first[i] = std::max(first[i], first[i - 1] + cells);
      idle += first[i] - first[i - 1] - cells;
    }
    EXPECT_EQ(res.accept_cycles[i], accept[i]) << "reading " << i << " (z = " << z[i] << ")";
    EXPECT_EQ(res.first_cells[i], first[i]) << "reading " << i << " (z = " << z[i] << ")";
  }
  EXPECT_EQ(res.idle_output_cycles, idle);
  std::printf(
      "[%s] back to back: %zu readings, y_valid low %llu cycles between cells, as "
      "scheduled\n",
      Config::name, z.size(), static_cast<unsigned long long>(idle));
}

TEST(SectoralIsmRtl, Cone16BackToBackFollowsTheScheduleExactly) {
  back_to_back_schedule<Vsectoral_ism_cone16, SectoralIsmCone16>();
}
TEST(SectoralIsmRtl, Cone12BackToBackFollowsTheScheduleExactly) {
  back_to_back_schedule<Vsectoral_ism_cone12, SectoralIsmCone12>();
}

// A bank written while the previous reading's last cells wait in the spill register, under
// back-pressure: each reading (past reach, 2 set-up cycles) is offered only once at most 2 cells
// of the one before are unsent. The intact RTL wastes no ready cycle; the fault
// stream_bubble (an empty stage 1 waits for the spill register) does, and its
// assertion fires.
template <class Model>
IsmBenchResult back_pressure_at_bank_starts(const char* what, std::string* log) {
  const IsmKernelTables& k = kernel_of("cone16");
  IsmRtlBench<Model> bench(k, trace_path());
  IsmBenchOptions opt;
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<SectoralIsmCone16>;
  opt.seed = ism_bench_seed(41, what);
  opt.ready = 0.5;
  opt.gap = 0.0;
  opt.offer_at_unsent = 2;
  std::vector<std::uint32_t> z(waves_on() ? 8 : 150);
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = k.reach + std::uint32_t(i);
  ::testing::internal::CaptureStdout();
  const IsmBenchResult r = bench.run(z, opt);
  *log = ::testing::internal::GetCapturedStdout();
  return r;
}

TEST(SectoralIsmRtl, Cone16BackPressureWastesNoReadyCycle) {
  std::string log;
  const IsmBenchResult r = back_pressure_at_bank_starts<Vsectoral_ism_cone16>("cone16", &log);
  EXPECT_TRUE(r.ok()) << r.summary() << "\n" << log;
  EXPECT_GT(r.readings, 0u);
}

TEST(SectoralIsmRtl, StreamBubbleIsCaught) {
  std::string log;
  const IsmBenchResult r =
      back_pressure_at_bank_starts<Vsectoral_ism_cone16_bubble>("cone16 bubble", &log);
  std::printf("[cone16 bubble] %s\n", r.summary().c_str());
  EXPECT_GT(r.wasted_cycles, 0u) << "the bench missed the bubble";
  EXPECT_GT(r.assertion_failures, 0u);
  EXPECT_NE(log.find("i_stream.bank_read_without_wait"), std::string::npos) << log.substr(0, 2000);
  EXPECT_EQ(r.mismatches, 0u);  // the values are right, only the timing is not
}

// z_ready is low from the first reset edge to the first cycle out of reset, with a reading
// offered all along, at power-up and in mid-stream.
TEST(SectoralIsmRtl, ReadyIsLowInReset) {
  const IsmKernelTables& k = kernel_of("cone16");
  IsmRtlBench<Vsectoral_ism_cone16> bench(k, trace_path());
  EXPECT_EQ(bench.reset(3, true), 0);
  IsmBenchOptions opt;
  opt.stop_after_cycles = 300;
  bench.run(ism_edge_readings(k, kIsmReadingBits), opt);
  EXPECT_EQ(bench.reset(2, true), 0);
  EXPECT_FALSE(bench.assertion_failed());
}

// The RTL with the fault ism_ready_in_reset (z_ready without the out-of-reset flag) fails
// the reset assertion in the bench's first reset already.
TEST(SectoralIsmRtlAssertions, ReadyInResetFiresReadyLowAfterResetEdge) {
  ::testing::internal::CaptureStdout();
  IsmRtlBench<Vsectoral_ism_cone12_ready> bench(kernel_of("cone12"));
  const int ready = bench.reset(2, true);
  const std::string log = ::testing::internal::GetCapturedStdout();
  EXPECT_GT(ready, 0);
  EXPECT_TRUE(bench.assertion_failed());
  EXPECT_NE(log.find("ready_low_after_reset_edge"), std::string::npos) << log;
}

// A reset in the middle of a set-up, of an output, or of both (the other bank), after which the
// kernel runs the whole stimulus exactly as from power-up: the same cells (golden), the same
// port values every cycle (hash), the same timing.
template <class Model, class Config>
void reset_in_mid_stream() {
  const IsmKernelTables& k = kernel_of(Config::name);
  const std::uint64_t seed = ism_bench_seed(23, Config::name);
  const std::vector<std::uint32_t> z = stimulus(k, 30, seed);
  IsmBenchOptions opt;
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
  opt.seed = seed;
  opt.ready = 0.7;
  opt.gap = 0.2;
  IsmRtlBench<Model> fresh(k);
  const IsmBenchResult want = fresh.run(z, opt);
  ASSERT_TRUE(want.ok()) << want.summary();
  ASSERT_GE(want.first_cells.size(), 2u);
  const std::uint64_t cells = k.grid.cells();
  const std::uint64_t stops[] = {
      want.accept_cycles[0] + 20,       // the first reading's set-up
      want.first_cells[0] + cells / 2,  // its output (the next set-up runs beside it)
      want.first_cells[1] + cells - 1,  // the second reading's output
      want.cycles * 2 / 3};
  for (const std::uint64_t stop : stops) {
    IsmRtlBench<Model> bench(k, trace_path());
    IsmBenchOptions part = opt;
    part.stop_after_cycles = stop;
    const IsmBenchResult before = bench.run(z, part);
    ASSERT_TRUE(before.stopped) << stop;
    EXPECT_TRUE(before.ok()) << before.summary();
    if (stop == stops[0]) {
      EXPECT_EQ(before.cells, 0u) << "not in the first set-up";
    } else if (stop != stops[3]) {
      EXPECT_GT(before.cells % cells, 0u) << "not in mid-output: " << stop;
    }
    EXPECT_EQ(bench.reset(1, true), 0) << "z_ready in reset, stop at " << stop;
    const IsmBenchResult got = bench.run(z, opt);
    EXPECT_TRUE(got.ok()) << "reset at " << stop << ": " << got.summary();
    EXPECT_EQ(got.port_hash, want.port_hash) << "reset at " << stop;
    EXPECT_EQ(got.cycles, want.cycles) << "reset at " << stop;
    EXPECT_EQ(got.latencies, want.latencies) << "reset at " << stop;
  }
}

TEST(SectoralIsmRtl, Cone16ResetInMidStreamRestartsAsFromPowerUp) {
  reset_in_mid_stream<Vsectoral_ism_cone16, SectoralIsmCone16>();
}
TEST(SectoralIsmRtl, Cone12ResetInMidStreamRestartsAsFromPowerUp) {
  reset_in_mid_stream<Vsectoral_ism_cone12, SectoralIsmCone12>();
}

// Random initial state (every register and RAM word, --x-initial unique, several seeds): after
// the reset the kernel behaves exactly as from an all-zero state.
template <class Model, class Config>
void random_initial_state() {
  const IsmKernelTables& k = kernel_of(Config::name);
  const std::vector<std::uint32_t> z = stimulus(k, 20, 5);
  IsmBenchOptions opt;
  opt.setup_cycles = &sc::sectoral_ism_setup_cycles<Config>;
  opt.seed = 5;
  IsmRtlBench<Model> zero(k);
  const IsmBenchResult want = zero.run(z, opt);
  ASSERT_TRUE(want.ok()) << want.summary();
  for (const int init : {1, 2, 3, 4}) {
    IsmRtlBench<Model> bench(k, trace_path(), init);
    const IsmBenchResult got = bench.run(z, opt);
    EXPECT_TRUE(got.ok()) << "initial state " << init << ": " << got.summary();
    EXPECT_EQ(got.port_hash, want.port_hash) << "initial state " << init;
  }
}

TEST(SectoralIsmRtl, Cone16RandomInitialStateIsReset) {
  random_initial_state<Vsectoral_ism_cone16, SectoralIsmCone16>();
}
TEST(SectoralIsmRtl, Cone12RandomInitialStateIsReset) {
  random_initial_state<Vsectoral_ism_cone12, SectoralIsmCone12>();
}

// The input rule's assertion is live: a reading changed while the kernel is busy.
TEST(SectoralIsmRtlAssertions, SourceChangingAnOfferedReadingFails) {
  const IsmKernelTables& k = kernel_of("cone16");
  IsmRtlBench<Vsectoral_ism_cone16> bench(k);
  auto& m = bench.model();
  m.z_valid_i = 1;
  m.z_data_i = 256;
  m.eval();
  ASSERT_TRUE(m.z_ready_o);
  bench.tick();  // taken: the engine is busy from here on
  ::testing::internal::CaptureStdout();
  bench.tick();  // offered, not taken
  m.z_data_i = 512;
  bench.tick();  // changed while still not taken
  const std::string log = ::testing::internal::GetCapturedStdout();
  EXPECT_TRUE(bench.assertion_failed());
  EXPECT_NE(log.find("z_source_holds"), std::string::npos) << log;
}

// The output stream alone (3 rings x 4 bins, 2 sectors) under random back-pressure, banks
// written again after random gaps. Returns what the simulation printed; *failed = an assertion
// failed.
template <class Model>
std::string drive_stream(std::uint64_t seed, bool* failed) {
  VerilatedContext context;
  context.fatalOnError(false);
  tb::use_verilated_context(&context);  // while m is built and destroyed
  Model m(&context);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution ready(0.5);
  std::uniform_int_distribution<int> gap(0, 3);
  m.clk_i = 0;
  m.rst_ni = 0;
  m.full_i = 0;
  m.r_lo_i = 2;
  m.r_hi_i = 2;
  m.below_i = 0x81;
  m.rdata_i = 0;
  m.y_ready_i = 0;
  const auto tick = [&] {
    const bool read = m.re_o;
    const unsigned addr = m.raddr_o;
    m.clk_i = 1;
    m.eval();
    if (read) m.rdata_i = static_cast<std::uint8_t>(addr * 7 + 1);  // a registered RAM read
    m.clk_i = 0;
    m.eval();
  };
  ::testing::internal::CaptureStdout();
  m.eval();
  for (int i = 0; i < 3; ++i) tick();
  m.rst_ni = 1;
  bool full = true;
  int wait = 0;
  for (int cycle = 0; cycle < 2000; ++cycle) {
    m.full_i = full;
    m.y_ready_i = ready(rng);
    m.eval();
    const bool release = m.release_o;
    tick();
    if (release) {
      full = false;
      wait = gap(rng);
    } else if (!full && wait-- <= 0) {
      full = true;
    }
  }
  *failed = context.gotError();
  m.final();
  return ::testing::internal::GetCapturedStdout();
}

TEST(SectoralIsmRtlAssertions, IntactStreamPasses) {
  bool failed = true;
  const std::string log = drive_stream<Vsectoral_ism_stream_none>(1, &failed);
  EXPECT_FALSE(failed) << log;
}
TEST(SectoralIsmRtlAssertions, StreamBubbleFiresBankReadWithoutWait) {
  bool failed = false;
  const std::string log = drive_stream<Vsectoral_ism_stream_stream_bubble>(1, &failed);
  EXPECT_TRUE(failed);
  EXPECT_NE(log.find(".bank_read_without_wait"), std::string::npos) << log;
}
TEST(SectoralIsmRtlAssertions, WrongLastFiresLastEveryReading) {
  bool failed = false;
  const std::string log = drive_stream<Vsectoral_ism_stream_stream_last>(1, &failed);
  EXPECT_TRUE(failed);
  EXPECT_NE(log.find(".last_every_reading"), std::string::npos) << log;
}
TEST(SectoralIsmRtlAssertions, OverwrittenStallFiresOutputStable) {
  bool failed = false;
  const std::string log = drive_stream<Vsectoral_ism_stream_spill_overwrite>(1, &failed);
  EXPECT_TRUE(failed);
  EXPECT_NE(log.find("i_spill.output_stable"), std::string::npos) << log;
}
TEST(SectoralIsmRtlAssertions, LateSpillFiresEntryOrderNoBubbleAndStageFeedsOutput) {
  bool failed = false;
  const std::string log = drive_stream<Vsectoral_ism_stream_spill_bubble>(1, &failed);
  EXPECT_TRUE(failed);
  EXPECT_NE(log.find("i_spill.entry_order"), std::string::npos) << log;
  EXPECT_NE(log.find("i_spill.no_bubble"), std::string::npos) << log;
  EXPECT_NE(log.find(".stage_feeds_output"), std::string::npos) << log;
}

}  // namespace
}  // namespace intgrid::hw
