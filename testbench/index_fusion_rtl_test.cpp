// Verilator testbench of rtl/index_fusion.sv, one Verilated model per (B, LANES) configuration
// (the list is in testbench/index_fusion.cmake), every output beat checked against golden
// intgrid::core::fuse_indices by the scoreboard of testbench/index_fusion_tb.hpp.
//
//   index_fusion_rtl_test [gtest flags]   the tests (ctest label hw)
//   index_fusion_rtl_test --report        one JSON line per configuration: cycles per beat and
//                                         per cell, latency, with back-pressure off and on, and
//                                         simulation speed (cells per second of host time)
//   --trace[=DIR] or INTGRID_WAVES=DIR     FST waveforms, one file per run in DIR (default .),
//                                         the first INTGRID_TB_TRACE_CYCLES cycles (default 20000)
// The models are verilated with --assert: a failed RTL assertion fails the run.
//   INTGRID_TB_SEED=N                      reproduce a run (every test prints its seed)
#include <verilated.h>
#include <verilated_fst_c.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "index_fusion_configs.hpp"  // generated: the Verilated models, INTGRID_INDEX_FUSION_CONFIGS
#include "testbench/index_fusion_tb.hpp"
#include "testbench/verilated_thread_context.hpp"

namespace {

using namespace intgrid::tb;

struct TraceOptions {
  bool on = false;
  std::string dir = ".";
  std::uint64_t cycles = 20000;
} g_trace;

struct SimOptions {
  Coverage coverage = Coverage::kRandom;
  std::uint64_t random_beats = 0;
  bool random_traffic = true;  // random valid gaps and back-pressure, in segments
  TrafficRates rates{};        // when !random_traffic
  std::uint64_t seed = 0;
  std::uint64_t stop_after_cycles = UINT64_MAX;  // leave the run early (to reset in mid-frame)
};

struct SimRun {
  FusionResult result;
  double host_seconds = 0.0;
};

// The wave file of a model: <suite>.<test> inside a test (.2, .3 ... for its next models),
// else the run's name.
inline std::string wave_name(const std::string& run) {
  static std::string test;
  static int models = 0;
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  if (info == nullptr) return run;
  const std::string name = std::string(info->test_suite_name()) + "." + info->name();
  models = name == test ? models + 1 : 1;
  test = name;
  return models > 1 ? name + "." + std::to_string(models) : name;
}

// One Verilated model with its clock, reset and optional FST trace.
template <class VModel, int B, int LANES>
class Harness {
 public:
  // init_seed: negative for an all-zero initial state, else the seed of a random one.
  explicit Harness(const std::string& name, int init_seed = -1) : top_(nullptr) {
    context_.traceEverOn(g_trace.on);
    context_.randReset(init_seed < 0 ? 0 : 2);
    if (init_seed >= 0) context_.randSeed(init_seed);
    context_.fatalOnError(false);      // a failed assertion fails the run, it does not abort
    use_verilated_context(&context_);  // while its model is built (see the function)
    top_ = std::make_unique<VModel>(&context_, "top");
    if (g_trace.on) {
      vcd_ = std::make_unique<VerilatedFstC>();
      top_->trace(vcd_.get(), 99);
      const std::string path = g_trace.dir + "/" + wave_name(name) + ".fst";
      vcd_->open(path.c_str());
      std::printf("[trace] %s\n", path.c_str());
    }
    top_->clk_i = 0;
    top_->eval();
  }
  ~Harness() {
    if (vcd_) vcd_->close();
    use_verilated_context(&context_);
    top_->final();
    top_.reset();
  }

  // Synchronous reset for `cycles` cycles, inputs idle unless `offer` (both valids high).
  // Returns the cycles of the reset in which a_ready or b_ready was high (the RTL promises none).
  int reset(int cycles, bool offer = false) {
    int ready = 0;
    top_->rst_ni = 0;
    top_->a_valid_i = offer;
    top_->b_valid_i = offer;
    top_->y_ready_i = 0;
    for (int i = 0; i < cycles; ++i) {
      top_->eval();
      ready += top_->a_ready_o || top_->b_ready_o;
      dump();
      tick();
    }
    top_->rst_ni = 1;
    return ready;
  }
  VModel& top() { return *top_; }
  bool assertion_failed() const { return context_.gotError(); }

  // Applies the inputs and returns the outputs they settle to (before the next rising edge).
  FusionOutputs apply(const FusionDrive<B, LANES>& d) {
    top_->a_valid_i = d.a_valid;
    top_->b_valid_i = d.b_valid;
    top_->y_ready_i = d.y_ready;
    top_->a_last_i = d.a_last;
    top_->b_last_i = d.b_last;
    to_port(top_->a_data_i, d.a_data);
    to_port(top_->b_data_i, d.b_data);
    top_->eval();
    dump();
    FusionOutputs out;
    out.a_ready = top_->a_ready_o;
    out.b_ready = top_->b_ready_o;
    out.y_valid = top_->y_valid_o;
    out.y_last = top_->y_last_o;
    out.y_data = from_port(top_->y_data_o);
    return out;
  }

  // One rising and one falling edge.
  void tick() {
    context_.timeInc(5);
    top_->clk_i = 1;
    top_->eval();
    dump();
    context_.timeInc(5);
    top_->clk_i = 0;
    top_->eval();
  }

 private:
  void dump() {
    if (vcd_ && context_.time() < 10 * g_trace.cycles) vcd_->dump(context_.time());
  }
  VerilatedContext context_;
  std::unique_ptr<VModel> top_;
  std::unique_ptr<VerilatedFstC> vcd_;
};

// Runs a stimulus through a model already out of reset; returns the scoreboard's verdict.
template <class VModel, int B, int LANES>
SimRun stream(Harness<VModel, B, LANES>& dut, const std::string& name, const SimOptions& opt) {
  const TrafficShaper traffic = opt.random_traffic ? TrafficShaper(splitmix64(opt.seed + 1))
                                                   : TrafficShaper::fixed(opt.rates);
  FusionDriver<B, LANES> driver(FusionStimulus<B, LANES>(opt.coverage, opt.random_beats, opt.seed),
                                traffic, splitmix64(opt.seed + 2));
  FusionScoreboard<B, LANES> board(name);

  const auto start = std::chrono::steady_clock::now();
  std::uint64_t idle = 0, tail = 0;
  while (true) {
    const FusionDrive<B, LANES>& d = driver.drive();
    const FusionOutputs out = dut.apply(d);
    const bool progress = out.y_valid && d.y_ready;
    const bool moved = board.observe(d, out);
    dut.tick();
    driver.advance(moved);
    if (dut.assertion_failed()) {
      board.stuck("an RTL assertion failed (its %Error line is printed above)");
      break;
    }
    if (board.cycle() >= opt.stop_after_cycles) break;

    idle = (moved || progress) ? 0 : idle + 1;
    if (idle > 20000) {
      board.stuck("no handshake for 20000 cycles");
      break;
    }
    if (board.protocol_errors() > 100) break;
    // After the last beat: 32 idle cycles in which nothing may come out.
    if (driver.finished() && board.in_flight() == 0 && ++tail > 32) break;
  }
  const auto stop = std::chrono::steady_clock::now();
  return SimRun{board.result(), std::chrono::duration<double>(stop - start).count()};
}

// A fresh model: reset, then the whole stimulus.
template <class VModel, int B, int LANES>
SimRun simulate(const std::string& name, const SimOptions& opt, int init_seed = -1) {
  Harness<VModel, B, LANES> dut(name, init_seed);
  dut.reset(3);
  return stream(dut, name, opt);
}

// Coverage of the issue: exhaustive where 2^(2B) <= 2^20 pairs, else at least 2^18 random beats
// (every lane gets its own random pair in each beat).
template <int B>
SimOptions default_options(const std::string& name) {
  SimOptions opt;
  opt.coverage = 2 * B <= 20 ? Coverage::kExhaustive : Coverage::kRandom;
  opt.random_beats = std::uint64_t{1} << 18;
  opt.seed = test_seed(name);
  return opt;
}

template <class VModel, int B, int LANES>
void check_config(const std::string& name) {
  const SimOptions opt = default_options<B>(name);
  const SimRun run = simulate<VModel, B, LANES>(name, opt);
  const FusionResult& r = run.result;
  std::printf("[%s] %s (%s), %.2f s\n", name.c_str(), r.summary().c_str(),
              opt.coverage == Coverage::kExhaustive ? "exhaustive per lane" : "random",
              run.host_seconds);
  EXPECT_TRUE(r.ok()) << r.summary();
  const std::uint64_t beats =
      opt.coverage == Coverage::kExhaustive ? FusionStimulus<B, LANES>::kPairs : opt.random_beats;
  EXPECT_EQ(r.beats_in, beats);
  EXPECT_EQ(r.beats_out, beats);
  EXPECT_EQ(r.cells_checked, beats * LANES);
}

#define INTGRID_DEFINE_CONFIG_TEST(Model, Bits, Lanes)                        \
  TEST(IndexFusionRtl, B##Bits##_Lanes##Lanes) {                              \
    check_config<Model, Bits, Lanes>("index_fusion_rtl_b" #Bits "_l" #Lanes); \
  }
INTGRID_INDEX_FUSION_CONFIGS(INTGRID_DEFINE_CONFIG_TEST)
#undef INTGRID_DEFINE_CONFIG_TEST

// Full rate (no gaps, no back-pressure): exactly one beat per cycle after a latency of one.
TEST(IndexFusionRtl, FullRateIsOneBeatPerCycle) {
  SimOptions opt;
  opt.random_beats = 4096;
  opt.random_traffic = false;
  opt.rates = TrafficRates{1.0, 1.0};
  opt.seed = test_seed("index_fusion_rtl_full_rate");
  const FusionResult r =
      simulate<Vindex_fusion_b8_l8, 8, 8>("index_fusion_rtl_full_rate", opt).result;
  ASSERT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.cycles, opt.random_beats + 1);  // beat k accepted at edge k, output at edge k + 1
  EXPECT_EQ(r.last_out_cycle - r.first_out_cycle, opt.random_beats - 1);
  EXPECT_EQ(r.latency.min, 1);
  EXPECT_EQ(r.latency.max, 1);
}

// Back-pressure only (inputs always valid, y_ready 30% of cycles): after the first beat, every
// cycle in which y_ready is high moves a beat out.
TEST(IndexFusionRtl, BackPressureWastesNoReadyCycle) {
  SimOptions opt;
  opt.random_beats = 8192;
  opt.random_traffic = false;
  opt.rates = TrafficRates{1.0, 0.3};
  opt.seed = test_seed("index_fusion_rtl_back_pressure");
  const FusionResult r =
      simulate<Vindex_fusion_b8_l8, 8, 8>("index_fusion_rtl_back_pressure", opt).result;
  ASSERT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.ready_cycles, r.beats_out);
}

// A reset in the middle of a stall empties the buffer: with two beats held (y_ready low, inputs
// refused), one reset cycle drops them, y_valid falls and the input is accepted again; a full
// stimulus then runs cleanly through the same model.
TEST(IndexFusionRtl, ResetEmptiesAStalledBuffer) {
  const std::string name = "index_fusion_rtl_reset";
  Harness<Vindex_fusion_b8_l8, 8, 8> dut(name);
  dut.reset(3);
  FusionDrive<8, 8> d;
  d.a_valid = d.b_valid = true;
  d.y_ready = false;
  d.a_data.w[0] = 0x01020304u;
  d.b_data.w[0] = 0x10203040u;
  EXPECT_TRUE(dut.apply(d).a_ready);  // empty: taken into entry a
  dut.tick();
  EXPECT_TRUE(dut.apply(d).a_ready);  // a stalls: taken into entry b
  dut.tick();
  FusionOutputs full = dut.apply(d);
  EXPECT_FALSE(full.a_ready);  // both entries held
  EXPECT_TRUE(full.y_valid);
  EXPECT_EQ(full.y_data.w[0], 0x11223344u);
  dut.reset(1);
  d.a_valid = d.b_valid = false;
  const FusionOutputs after = dut.apply(d);
  EXPECT_FALSE(after.y_valid);
  d.a_valid = d.b_valid = true;
  EXPECT_TRUE(dut.apply(d).a_ready);
  SimOptions opt;
  opt.random_beats = 20000;
  opt.seed = test_seed(name);
  const FusionResult r = stream(dut, name, opt).result;
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.beats_out, opt.random_beats);
}

// Ready is low in every cycle of a reset, both valids high, from power-up (before the first
// edge) and in mid-frame; right after it a beat is taken at once.
TEST(IndexFusionRtl, ReadyIsLowInReset) {
  Harness<Vindex_fusion_b8_l8, 8, 8> dut("index_fusion_rtl_ready_in_reset", 7);
  EXPECT_EQ(dut.reset(3, true), 0);
  FusionDrive<8, 8> d;
  d.a_valid = d.b_valid = d.y_ready = true;
  EXPECT_TRUE(dut.apply(d).a_ready);
  dut.tick();
  EXPECT_EQ(dut.reset(2, true), 0);
  EXPECT_TRUE(dut.apply(d).a_ready);
  EXPECT_FALSE(dut.assertion_failed());
}

// Resets in mid-frame under random traffic (one reset cycle), each followed by the whole stimulus:
// the same verdict, cycles and latencies as a model fresh from power-up; and random initial states
// (--x-initial unique, four seeds) reset to the same behaviour.
TEST(IndexFusionRtl, ResetInMidFrameRestartsAsFromPowerUp) {
  const std::string name = "index_fusion_rtl_mid_frame_reset";
  SimOptions opt;
  opt.random_beats = 6000;
  opt.seed = test_seed(name);
  const FusionResult want = simulate<Vindex_fusion_b8_l8, 8, 8>(name, opt).result;
  ASSERT_TRUE(want.ok()) << want.summary();
  const auto same = [&](const FusionResult& got, const std::string& what) {
    EXPECT_TRUE(got.ok()) << what << ": " << got.summary();
    EXPECT_EQ(got.cycles, want.cycles) << what;
    EXPECT_EQ(got.first_out_cycle, want.first_out_cycle) << what;
    EXPECT_EQ(got.ready_cycles, want.ready_cycles) << what;
    EXPECT_EQ(got.latency.sum, want.latency.sum) << what;
    EXPECT_EQ(got.latency.max, want.latency.max) << what;
  };
  for (const std::uint64_t stop : {want.cycles / 7, want.cycles / 3, want.cycles * 5 / 6}) {
    Harness<Vindex_fusion_b8_l8, 8, 8> dut(name);
    dut.reset(3);
    SimOptions part = opt;
    part.stop_after_cycles = stop;
    stream(dut, name, part);
    EXPECT_EQ(dut.reset(1, true), 0);
    same(stream(dut, name, opt).result, "reset at cycle " + std::to_string(stop));
  }
  for (const int init : {1, 2, 3, 4})
    same(simulate<Vindex_fusion_b8_l8, 8, 8>(name, opt, init).result,
         "initial state " + std::to_string(init));
}

// The sources' rule is checked by the RTL: a changing a beat it offers before the join takes it
// (b not yet valid) fails an assertion.
TEST(IndexFusionRtlAssertions, SourceChangingAnOfferedBeatFails) {
  Harness<Vindex_fusion_b8_l8, 8, 8> dut("index_fusion_rtl_source_rule");
  dut.reset(3);
  FusionDrive<8, 8> d;
  d.a_valid = true;
  d.a_data.w[0] = 1;
  EXPECT_FALSE(dut.apply(d).a_ready);
  testing::internal::CaptureStdout();
  dut.tick();
  d.a_data.w[0] = 2;
  dut.apply(d);
  dut.tick();
  const std::string log = testing::internal::GetCapturedStdout();
  EXPECT_TRUE(dut.assertion_failed());
  EXPECT_NE(log.find("a_source_holds"), std::string::npos) << log;
}

TEST(IndexFusionRtlAssertions, SourceBChangingAnOfferedBeatFails) {
  Harness<Vindex_fusion_b8_l8, 8, 8> dut("index_fusion_rtl_source_rule_b");
  dut.reset(3);
  FusionDrive<8, 8> d;
  d.b_valid = true;
  d.b_last = false;
  EXPECT_FALSE(dut.apply(d).b_ready);
  testing::internal::CaptureStdout();
  dut.tick();
  d.b_last = true;
  dut.apply(d);
  dut.tick();
  const std::string log = testing::internal::GetCapturedStdout();
  EXPECT_TRUE(dut.assertion_failed());
  EXPECT_NE(log.find("b_source_holds"), std::string::npos) << log;
}

// The RTL with the faults fusion_ready_in_reset and spill_refuse (testbench/rtl_faults.cmake):
// ready during reset, and a beat refused while entry b is free, each fire their assertion.
TEST(IndexFusionRtlAssertions, ReadyInResetFiresReadyLowInReset) {
  Harness<Vindex_fusion_fault_protocol_b4_l1, 4, 1> dut("index_fusion_rtl_fault_ready");
  testing::internal::CaptureStdout();
  const int ready = dut.reset(3, true);
  const std::string log = testing::internal::GetCapturedStdout();
  EXPECT_GT(ready, 0);
  EXPECT_TRUE(dut.assertion_failed());
  EXPECT_NE(log.find("ready_low_in_reset"), std::string::npos) << log;
}
TEST(IndexFusionRtlAssertions, RefusingSpillRegisterFiresJoinTakesBeat) {
  Harness<Vindex_fusion_fault_protocol_b4_l1, 4, 1> dut("index_fusion_rtl_fault_refuse");
  dut.reset(3);  // valids low: the fault in reset has nothing to accept
  ASSERT_FALSE(dut.assertion_failed());
  FusionDrive<4, 1> d;
  d.a_valid = d.b_valid = true;
  testing::internal::CaptureStdout();
  EXPECT_TRUE(dut.apply(d).a_ready);  // empty: taken into entry a
  dut.tick();
  EXPECT_FALSE(dut.apply(d).a_ready);  // entry b is free, yet refused
  dut.tick();
  const std::string log = testing::internal::GetCapturedStdout();
  EXPECT_TRUE(dut.assertion_failed());
  EXPECT_NE(log.find("join_takes_beat"), std::string::npos) << log;
}

// The checker's self-test: the RTL built with saturation_bound lets a sum of exactly
// -2^(B-1) through unsaturated. Over the exhaustive run every lane meets each of the 129 pairs
// with a + b = -128 once, so the scoreboard must report exactly 129 * LANES mismatching cells,
// and nothing else.
TEST(IndexFusionRtlFault, CheckerCatchesWrongNegativeBound) {
  constexpr int kB = 8, kLanes = 8;
  const std::string name = "index_fusion_rtl_fault_b8_l8";
  const SimOptions opt = default_options<kB>(name);
  const FusionResult r = simulate<Vindex_fusion_fault_b8_l8, kB, kLanes>(name, opt).result;
  std::printf("[%s] %s\n", name.c_str(), r.summary().c_str());
  int pairs_at_min = 0;
  for (int a = -128; a <= 127; ++a)
    for (int b = -128; b <= 127; ++b) pairs_at_min += (a + b == -128);
  ASSERT_EQ(pairs_at_min, 129);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.cell_mismatches, std::uint64_t{129} * kLanes);
  EXPECT_EQ(r.protocol_errors, 0u);
  EXPECT_EQ(r.last_mismatches, 0u);
  EXPECT_EQ(r.beats_out, (FusionStimulus<kB, kLanes>::kPairs));
}

// --report: one JSON line per configuration.
template <class VModel, int B, int LANES>
void report(const char* model) {
  const std::string base =
      "index_fusion_report_b" + std::to_string(B) + "_l" + std::to_string(LANES);
  SimOptions opt;
  opt.random_beats = std::uint64_t{1} << 17;
  opt.random_traffic = false;
  opt.seed = splitmix64(master_seed() ^ (B * 100 + LANES));
  opt.rates = TrafficRates{1.0, 1.0};
  const SimRun off = simulate<VModel, B, LANES>(base + "_bp_off", opt);
  opt.rates = TrafficRates{1.0, 0.5};
  const SimRun on = simulate<VModel, B, LANES>(base + "_bp_on", opt);
  auto part = [](const SimRun& run, double ready) {
    const FusionResult& r = run.result;
    const double beats = static_cast<double>(r.beats_out);
    char buf[512];
    std::snprintf(
        buf, sizeof buf,
        "{\"y_ready_rate\":%.2f,\"ok\":%s,\"cycles\":%llu,\"cycles_per_beat\":%.5f,"
        "\"cycles_per_cell\":%.5f,\"steady_ii\":%.5f,\"ready_cycles_per_beat\":%.5f,"
        "\"latency_cycles\":%s,\"sim_cells_per_s\":%.4g,\"sim_cycles_per_s\":%.4g}",
        ready, r.ok() ? "true" : "false", static_cast<unsigned long long>(r.cycles),
        static_cast<double>(r.cycles) / beats, static_cast<double>(r.cycles) / (beats * LANES),
        static_cast<double>(r.last_out_cycle - r.first_out_cycle) / (beats - 1.0),
        static_cast<double>(r.ready_cycles) / beats, r.latency.json().c_str(),
        beats * LANES / run.host_seconds, static_cast<double>(r.cycles) / run.host_seconds);
    return std::string(buf);
  };
  std::printf(
      "{\"kernel\":\"index_fusion\",\"model\":\"%s\",\"simulator\":\"verilator %s\",\"B\":%d,"
      "\"LANES\":%d,\"beats\":%llu,\"cells\":%llu,\"bp_off\":%s,\"bp_on\":%s}\n",
      model, Verilated::productVersion(), B, LANES,
      static_cast<unsigned long long>(opt.random_beats),
      static_cast<unsigned long long>(opt.random_beats * LANES), part(off, 1.0).c_str(),
      part(on, 0.5).c_str());
  std::fflush(stdout);
}

// A failing test says how to see its waves (one test, its own FST files).
class WavesHint : public testing::EmptyTestEventListener {
  void OnTestEnd(const testing::TestInfo& info) override {
    if (info.result()->Failed() && !g_trace.on)
      std::printf("[waves] INTGRID_WAVES=<dir> index_fusion_rtl_test --gtest_filter=%s.%s\n",
                  info.test_suite_name(), info.name());
  }
};

}  // namespace

int main(int argc, char** argv) {
  bool want_report = false;
  if (const char* env = std::getenv("INTGRID_WAVES"); env != nullptr && *env != '\0') {
    g_trace.on = true;
    if (std::strcmp(env, "1") != 0) g_trace.dir = env;
  }
  if (const char* env = std::getenv("INTGRID_TB_TRACE_CYCLES"); env != nullptr)
    g_trace.cycles = std::strtoull(env, nullptr, 0);
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--report") {
      want_report = true;
    } else if (arg == "--trace") {
      g_trace.on = true;
    } else if (arg.rfind("--trace=", 0) == 0) {
      g_trace.on = true;
      g_trace.dir = arg.substr(8);
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (want_report) {
#define INTGRID_REPORT_CONFIG(Model, B, LANES) report<Model, B, LANES>("rtl");
    INTGRID_INDEX_FUSION_CONFIGS(INTGRID_REPORT_CONFIG)
#undef INTGRID_REPORT_CONFIG
    return 0;
  }
  testing::InitGoogleTest(&argc, argv);
  testing::UnitTest::GetInstance()->listeners().Append(new WavesHint);
  return RUN_ALL_TESTS();
}
