// Self-test of the index-fusion testbench (testbench/index_fusion_tb.hpp) without a simulator: a
// C++ model of the RTL's micro-architecture (join, saturating adders from hls/, two-entry spill
// register) runs through the same driver and scoreboard as the Verilated RTL. Intact, it must pass;
// with each protocol fault injected, the scoreboard must report it. (The data-path fault is shown
// on the real RTL: IndexFusionRtlFault.CheckerCatchesWrongNegativeBound.)
#include <cstdint>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "hls/index_fusion.hpp"
#include "testbench/index_fusion_tb.hpp"

namespace {

using namespace intgrid::tb;

enum class Fault { kNone, kDrop, kDuplicate, kUnstable, kSplitJoin, kBubble, kWrongLast };

constexpr int kB = 8, kLanes = 4;

// rtl/index_fusion.sv as a C++ cycle model, with one optional fault.
class FusionModel {
 public:
  explicit FusionModel(Fault fault) : fault_(fault) {}

  // Combinational outputs for the current inputs.
  FusionOutputs outputs(const FusionDrive<kB, kLanes>& d) const {
    FusionOutputs o;
    const bool room = !b_full_ && !(fault_ == Fault::kBubble && cycle_ % 7 == 3);
    o.a_ready = d.a_valid && d.b_valid && room;
    o.b_ready = o.a_ready;
    if (fault_ == Fault::kSplitJoin && cycle_ > 50) o.a_ready = d.a_valid && room;
    o.y_valid = a_full_;
    o.y_data = a_.data;
    o.y_last = a_.last;
    if (fault_ == Fault::kUnstable && a_full_ && stalled_ > 0) o.y_data.w[0] ^= 1u;
    return o;
  }

  // The rising edge.
  void clock(const FusionDrive<kB, kLanes>& d) {
    const FusionOutputs o = outputs(d);
    const bool fire = o.a_ready && d.a_valid && (o.b_ready && d.b_valid);
    const bool a_drain =
        a_full_ && d.y_ready && !(fault_ == Fault::kDuplicate && beats_out_ == 100);
    if (a_full_ && d.y_ready) ++beats_out_;
    const bool a_fill = fire && (!a_full_ || a_drain) && !b_full_;
    const bool b_fill = fire && a_full_ && !a_drain;
    const bool b_drain = b_full_ && (!a_full_ || a_drain);
    Entry in;
    if (fire) {
      in.data = fuse(d.a_data, d.b_data);
      in.last = fault_ == Fault::kWrongLast ? d.b_last : d.a_last;
      ++beats_in_;
    }
    const bool drop = fault_ == Fault::kDrop && fire && beats_in_ == 100;
    if (b_drain) {
      a_ = b_;
    } else if (a_fill && !drop) {
      a_ = in;
    }
    a_full_ = b_drain || (a_fill && !drop) || (a_full_ && !a_drain);
    if (b_fill && !drop) b_ = in;
    b_full_ = (b_fill && !drop) || (b_full_ && !b_drain);
    stalled_ = a_full_ && !d.y_ready ? stalled_ + 1 : 0;
    ++cycle_;
  }

 private:
  struct Entry {
    Bits data;
    bool last = false;
  };
  static Bits fuse(const Bits& a, const Bits& b) {
    Bits y;
    for (int l = 0; l < kLanes; ++l)
      y.set_field(l * kB, kB,
                  intgrid::hls::saturating_add<kB>(a.field(l * kB, kB), b.field(l * kB, kB)));
    return y;
  }
  Fault fault_;
  Entry a_, b_;
  bool a_full_ = false, b_full_ = false;
  std::uint64_t cycle_ = 0, stalled_ = 0, beats_in_ = 0, beats_out_ = 0;
};

FusionResult run(Fault fault, std::uint64_t seed) {
  FusionModel model(fault);
  FusionDriver<kB, kLanes> driver(FusionStimulus<kB, kLanes>(Coverage::kRandom, 5000, seed),
                                  TrafficShaper(splitmix64(seed + 1), 50), splitmix64(seed + 2));
  FusionScoreboard<kB, kLanes> board("model");
  std::uint64_t tail = 0;
  for (int cycle = 0; cycle < 200000; ++cycle) {
    const FusionDrive<kB, kLanes> d = driver.drive();
    const bool moved = board.observe(d, model.outputs(d));
    model.clock(d);
    driver.advance(moved);
    if (driver.finished() && board.in_flight() == 0 && ++tail > 32) break;
  }
  const FusionResult r = board.result();
  static constexpr const char* kNames[] = {"none",       "drop",   "duplicate", "unstable",
                                           "split join", "bubble", "wrong last"};
  std::printf("[fault: %s] %s\n", kNames[static_cast<int>(fault)],
              r.messages.empty() ? "no error reported" : r.messages.front().c_str());
  return r;
}

TEST(IndexFusionChecker, PassesTheIntactModel) {
  const FusionResult r = run(Fault::kNone, test_seed("index_fusion_checker_intact"));
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_EQ(r.beats_out, 5000u);
}

TEST(IndexFusionChecker, ReportsEveryInjectedProtocolFault) {
  const std::uint64_t seed = test_seed("index_fusion_checker_faults");
  const FusionResult drop = run(Fault::kDrop, seed);
  EXPECT_FALSE(drop.ok());
  EXPECT_GT(drop.protocol_errors + drop.cell_mismatches, 0u) << "dropped beat: " << drop.summary();
  const FusionResult dup = run(Fault::kDuplicate, seed);
  EXPECT_FALSE(dup.ok());
  EXPECT_GT(dup.protocol_errors, 0u) << "duplicated beat: " << dup.summary();
  const FusionResult unstable = run(Fault::kUnstable, seed);
  EXPECT_FALSE(unstable.ok());
  EXPECT_GT(unstable.protocol_errors, 0u) << "unstable output: " << unstable.summary();
  const FusionResult split = run(Fault::kSplitJoin, seed);
  EXPECT_FALSE(split.ok());
  EXPECT_GT(split.protocol_errors, 0u) << "a taken without b: " << split.summary();
  const FusionResult bubble = run(Fault::kBubble, seed);
  EXPECT_FALSE(bubble.ok());
  EXPECT_GT(bubble.protocol_errors, 0u) << "bubble: " << bubble.summary();
  const FusionResult last = run(Fault::kWrongLast, seed);
  EXPECT_FALSE(last.ok());
  EXPECT_GT(last.last_mismatches, 0u) << "y_last from b: " << last.summary();
  EXPECT_EQ(last.cell_mismatches, 0u);
}

}  // namespace
