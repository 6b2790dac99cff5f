// The index-fusion testbench, independent of the simulator: stimulus, the driver of the two input
// streams and of the output's ready, and a scoreboard that checks every cycle of one model (RTL
// under Verilator, or the SystemC model) against golden intgrid::core::fuse_indices.
//
// Per cycle the harness (1) puts driver.drive() on the inputs, (2) lets the combinational logic
// settle, (3) hands the settled outputs to scoreboard.observe(), which returns whether the input
// beat moved at the coming clock edge, (4) clocks the model, (5) calls driver.advance(moved).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/core/seps.hpp"
#include "testbench/stream_driver.hpp"

namespace intgrid::tb {

// Exhaustive: every lane sees every (a, b) pair of B-bit indices exactly once, 2^(2B) beats
// (lane l of beat k gets pair (k + l * stride) mod 2^(2B)). Random: `random_beats` beats of
// uniform pairs, one in four lane values drawn from the corners (-2^(B-1), -max, -max+1, -1, 0, 1,
// max-1, max).
enum class Coverage { kExhaustive, kRandom };

template <int B, int LANES>
struct FusionBeat {
  std::array<std::int32_t, LANES> a{}, b{};
  bool a_last = false, b_last = false;
};

template <int B, int LANES>
class FusionStimulus {
 public:
  static constexpr std::int32_t kMin = -(1 << (B - 1));     // legal input, saturates
  static constexpr std::int32_t kMax = (1 << (B - 1)) - 1;  // the saturation bound
  static constexpr std::uint64_t kPairs = std::uint64_t{1} << (2 * B);

  FusionStimulus(Coverage coverage, std::uint64_t random_beats, std::uint64_t seed)
      : coverage_(coverage),
        beats_(coverage == Coverage::kExhaustive ? kPairs : random_beats),
        rng_(seed) {
    frame_ = std::uniform_int_distribution<std::uint64_t>(1, 64)(rng_);
  }
  std::uint64_t beats() const { return beats_; }
  Coverage coverage() const { return coverage_; }

  // Beat k; call with k = 0, 1, 2, ... in order.
  FusionBeat<B, LANES> make(std::uint64_t k) {
    FusionBeat<B, LANES> beat;
    for (int l = 0; l < LANES; ++l) {
      const auto lane = static_cast<std::size_t>(l);
      if (coverage_ == Coverage::kExhaustive) {
        const std::uint64_t stride = kPairs / LANES + 1;
        const std::uint64_t q = (k + static_cast<std::uint64_t>(l) * stride) % kPairs;
        beat.a[lane] = kMin + static_cast<std::int32_t>(q >> B);
        beat.b[lane] = kMin + static_cast<std::int32_t>(q & ((std::uint64_t{1} << B) - 1u));
      } else {
        beat.a[lane] = random_index();
        beat.b[lane] = random_index();
      }
    }
    // Frames of a random length per run; b's last disagrees with a's one beat in 16: the output
    // frames must follow a (rtl/index_fusion.sv).
    beat.a_last = (k % frame_ == frame_ - 1) || k + 1 == beats_;
    beat.b_last = beat.a_last != (std::uniform_int_distribution<int>(0, 15)(rng_) == 0);
    return beat;
  }

 private:
  std::int32_t random_index() {
    static constexpr std::array<std::int32_t, 8> kCorners{kMin, -kMax, -kMax + 1, -1,
                                                          0,    1,     kMax - 1,  kMax};
    if (std::uniform_int_distribution<int>(0, 3)(rng_) == 0)
      return kCorners[std::uniform_int_distribution<std::size_t>(0, kCorners.size() - 1)(rng_)];
    return std::uniform_int_distribution<std::int32_t>(kMin, kMax)(rng_);
  }
  Coverage coverage_;
  std::uint64_t beats_;
  std::uint64_t frame_ = 1;
  Rng rng_;
};

// Packs B-bit lanes into a bus (lane l at bits [l*B + B-1 : l*B]).
template <int B, int LANES>
Bits pack_lanes(const std::array<std::int32_t, LANES>& lanes) {
  Bits bits;
  for (int l = 0; l < LANES; ++l)
    bits.set_field(l * B, B, static_cast<std::uint32_t>(lanes[static_cast<std::size_t>(l)]));
  return bits;
}

// What the testbench puts on the model's inputs in one cycle.
template <int B, int LANES>
struct FusionDrive {
  bool a_valid = false, b_valid = false, y_ready = false;
  bool a_last = false, b_last = false;
  Bits a_data, b_data;
  FusionBeat<B, LANES> beat;  // the beat on offer (meaningful while a_valid || b_valid)
};

// The model's outputs, settled before a rising clock edge.
struct FusionOutputs {
  bool a_ready = false, b_ready = false;
  bool y_valid = false, y_last = false;
  Bits y_data;
  bool operator==(const FusionOutputs&) const = default;
};

// Drives a and b (independent random valid gaps; both streams carry the same sequence of beats)
// and y_ready (random back-pressure). While a stream's valid is low its data and last are junk.
template <int B, int LANES>
class FusionDriver {
 public:
  FusionDriver(FusionStimulus<B, LANES> stimulus, TrafficShaper traffic, std::uint64_t seed)
      : stimulus_(std::move(stimulus)), traffic_(std::move(traffic)), rng_(seed) {
    if (stimulus_.beats() > 0) current_ = stimulus_.make(0);
    step_gates(false);
  }
  const FusionDrive<B, LANES>& drive() const { return drive_; }
  // Every beat has been taken by the model.
  bool finished() const { return next_ >= stimulus_.beats(); }
  std::uint64_t beats() const { return stimulus_.beats(); }

  // After a clock edge; `moved` = the beat was taken at that edge.
  void advance(bool moved) {
    if (moved) {
      ++next_;
      if (!finished()) current_ = stimulus_.make(next_);
    }
    step_gates(moved);
  }

 private:
  void step_gates(bool moved) {
    const TrafficRates& rates = traffic_.next();
    a_gate_.step(moved, !finished(), rates.valid, rng_);
    b_gate_.step(moved, !finished(), rates.valid, rng_);
    drive_.a_valid = a_gate_.valid();
    drive_.b_valid = b_gate_.valid();
    drive_.y_ready = chance(rng_, rates.ready);
    drive_.beat = current_;
    const Bits real_a = pack_lanes<B, LANES>(current_.a), real_b = pack_lanes<B, LANES>(current_.b);
    drive_.a_data = drive_.a_valid ? real_a : junk();
    drive_.b_data = drive_.b_valid ? real_b : junk();
    drive_.a_last = drive_.a_valid ? current_.a_last : chance(rng_, 0.5);
    drive_.b_last = drive_.b_valid ? current_.b_last : chance(rng_, 0.5);
  }
  Bits junk() {
    Bits bits;
    for (int l = 0; l < LANES; ++l) bits.set_field(l * B, B, static_cast<std::uint32_t>(rng_()));
    return bits;
  }

  FusionStimulus<B, LANES> stimulus_;
  TrafficShaper traffic_;
  Rng rng_;
  ValidGate a_gate_, b_gate_;
  FusionBeat<B, LANES> current_;
  std::uint64_t next_ = 0;
  FusionDrive<B, LANES> drive_;
};

struct FusionResult {
  std::uint64_t beats_in = 0, beats_out = 0;
  std::uint64_t cells_checked = 0, cell_mismatches = 0, last_mismatches = 0;
  std::uint64_t protocol_errors = 0;  // stability, join, bubbles, drops, duplicates
  std::uint64_t cycles = 0;           // from the first cycle after reset to the last output beat
  std::uint64_t first_out_cycle = 0, last_out_cycle = 0;
  // Cycles with y_ready high after the first input beat's cycle, up to the last output beat: with
  // inputs always valid, equal to beats_out when no ready cycle is wasted.
  std::uint64_t ready_cycles = 0;
  Stats latency;                      // edges from a beat's input handshake to its output handshake
  std::vector<std::string> messages;  // the first few errors
  bool ok() const {
    return cell_mismatches == 0 && last_mismatches == 0 && protocol_errors == 0 &&
           beats_in == beats_out;
  }
  std::string summary() const {
    std::string s = "beats in " + std::to_string(beats_in) + ", out " + std::to_string(beats_out) +
                    ", cells checked " + std::to_string(cells_checked) + ", cell mismatches " +
                    std::to_string(cell_mismatches) + ", last mismatches " +
                    std::to_string(last_mismatches) + ", protocol errors " +
                    std::to_string(protocol_errors) + ", cycles " + std::to_string(cycles);
    for (const std::string& m : messages) s += "\n  " + m;
    return s;
  }
};

// Checks one model, cycle by cycle:
// - every output beat equals golden fuse_indices lane by lane, and its last equals a_last;
// - beats come out in order, none dropped (all in flight are output by the end), none duplicated
//   (no output beat without one in flight);
// - a and b are consumed together (a_valid && a_ready iff b_valid && b_ready);
// - y_valid, y_data, y_last hold while y_valid && !y_ready;
// - no bubble (II = 1): y_valid is high whenever a beat is in flight, and the input is taken
//   whenever both valids are high and fewer than two beats are in flight (the output buffer's
//   two entries).
template <int B, int LANES>
class FusionScoreboard {
 public:
  static constexpr int kMax = (1 << (B - 1)) - 1;
  explicit FusionScoreboard(std::string name, std::size_t max_messages = 12)
      : name_(std::move(name)), max_messages_(max_messages) {}

  // One cycle: the drive and the outputs settled before the edge. Returns whether the input beat
  // moves at that edge.
  bool observe(const FusionDrive<B, LANES>& d, const FusionOutputs& o) {
    const bool a_fire = d.a_valid && o.a_ready;
    const bool b_fire = d.b_valid && o.b_ready;
    const bool y_fire = o.y_valid && d.y_ready;
    const std::size_t in_flight = flight_.size();

    if (a_fire != b_fire)
      error("a and b consumed separately (a_fire " + bit(a_fire) + ", b_fire " + bit(b_fire) + ")");
    if (!stability_.check(o.y_valid, d.y_ready, Payload{o.y_data, o.y_last}))
      error("y changed while y_valid && !y_ready");
    if (o.y_valid && in_flight == 0) error("y_valid with no beat in flight (duplicate)");
    if (!o.y_valid && in_flight > 0) error("y_valid low with a beat in flight (bubble)");
    if (d.a_valid && d.b_valid && in_flight < 2 && !a_fire)
      error("input refused with room in the output buffer (bubble, II > 1)");
    if (in_flight > 2) error("more than two beats in flight");

    if (y_fire && in_flight > 0) {
      const InFlight& f = flight_.front();
      for (int l = 0; l < LANES; ++l) {
        const auto lane = static_cast<std::size_t>(l);
        const int want = intgrid::core::fuse_indices<int>(f.beat.a[lane], f.beat.b[lane], kMax);
        const int got = sign_extend(o.y_data.field(l * B, B), B);
        ++result_.cells_checked;
        if (got != want) {
          ++result_.cell_mismatches;
          note("beat " + std::to_string(result_.beats_out) + " lane " + std::to_string(l) +
               ": sat(" + std::to_string(f.beat.a[lane]) + " + " + std::to_string(f.beat.b[lane]) +
               ") = " + std::to_string(got) + ", golden " + std::to_string(want));
        }
      }
      if (o.y_last != f.beat.a_last) {
        ++result_.last_mismatches;
        note("beat " + std::to_string(result_.beats_out) + ": y_last " + bit(o.y_last) +
             ", a_last was " + bit(f.beat.a_last));
      }
      result_.latency.add(static_cast<std::int64_t>(cycle_ - f.cycle));
      if (result_.beats_out == 0) result_.first_out_cycle = cycle_;
      result_.last_out_cycle = cycle_;
      ++result_.beats_out;
      result_.cycles = cycle_ + 1;
      flight_.pop_front();
    }
    if (d.y_ready && result_.beats_in > 0 && cycle_ > first_in_cycle_) ++ready_cycles_;
    if (y_fire) result_.ready_cycles = ready_cycles_;
    if (a_fire) {
      if (result_.beats_in == 0) first_in_cycle_ = cycle_;
      flight_.push_back(InFlight{d.beat, cycle_});
      ++result_.beats_in;
    }
    ++cycle_;
    return a_fire && b_fire;
  }

  std::size_t in_flight() const { return flight_.size(); }
  std::uint64_t cycle() const { return cycle_; }
  std::uint64_t protocol_errors() const { return result_.protocol_errors; }
  // The result; beats still in flight count as dropped.
  FusionResult result() const {
    FusionResult r = result_;
    if (!flight_.empty()) {
      ++r.protocol_errors;
      r.messages.push_back(name_ + ": " + std::to_string(flight_.size()) +
                           " beat(s) never came out (dropped)");
    }
    return r;
  }
  // Marks the run as stuck (no progress): counted as a protocol error.
  void stuck(const std::string& why) { error(why); }

 private:
  struct Payload {
    Bits data;
    bool last = false;
    bool operator==(const Payload&) const = default;
  };
  struct InFlight {
    FusionBeat<B, LANES> beat;
    std::uint64_t cycle;
  };
  static std::string bit(bool b) { return b ? "1" : "0"; }
  void error(const std::string& what) {
    ++result_.protocol_errors;
    note(what);
  }
  void note(const std::string& what) {
    if (result_.messages.size() < max_messages_)
      result_.messages.push_back(name_ + ": cycle " + std::to_string(cycle_) + ": " + what);
  }

  std::string name_;
  std::size_t max_messages_;
  std::deque<InFlight> flight_;
  StabilityMonitor<Payload> stability_;
  std::uint64_t cycle_ = 0;
  std::uint64_t ready_cycles_ = 0;
  std::uint64_t first_in_cycle_ = 0;
  FusionResult result_;
};

}  // namespace intgrid::tb
