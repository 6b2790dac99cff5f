// Unit tests of the RTL sub-modules, each Verilated as its own top
// (testbench/sectoral_ism_units.cmake) and driven at its ports, against an oracle that is not the
// RTL's own arithmetic:
//   sectoral_ism_log_add  golden kernel_log_add: every distance d over twice the Phi ROM's address
//                         range in both orders, distances that alias into the table modulo its
//                         size, the word's limits, random pairs, log 0 on either side and both
//   sectoral_ism_index    golden kernel_index_of_log_odds (a search of the thresholds, not the
//                         bucket ROM): every odds magnitude up to two buckets past the last
//                         threshold in both signs (so every threshold, threshold +- 1 and bucket
//                         boundary), the widest odds the word holds, random pairs, log 0
//   sectoral_ism_density  hls::ism_log_density on every ring of the window of every reading below
//                         reach, driven on the set-up engine's schedule with random slot lengths
//   sectoral_ism_mul      the product in 64 bits: corners and random operands at the
//   configurations'
//                         widths, every operand pair at three small shapes
//   spill_register        a two-entry FIFO model, cycle by cycle, and no combinational path
//   saturating_add        golden fuse_indices, every pair for B = 4 and 8, random ones for B = 16
// The pipelined units run with random input gaps (garbage on the data ports while valid is low),
// exact latency checks (no output that was not asked for) and rare resets in mid-stream that
// must cancel everything in flight. The IsmUnitsFault tests run the same checks on sub-modules
// with one injected fault each and require them to fail. Every test prints its seed;
// INTGRID_ISM_SEED replays one.
#include <gtest/gtest.h>
#include <verilated.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vdensity_cone12.h"
#include "Vdensity_cone16.h"
#include "Vindex_cone12.h"
#include "Vindex_cone16.h"
#include "Vindex_fault_both_zero.h"
#include "Vindex_fault_den_zero.h"
#include "Vindex_fault_num_zero.h"
#include "Vlog_add_cone12.h"
#include "Vlog_add_cone16.h"
#include "Vlog_add_fault_both_zero.h"
#include "Vlog_add_fault_pass_a.h"
#include "Vmul_a4_b6_k1.h"
#include "Vmul_a5_b7_k7.h"
#include "Vmul_a6_b5_k2.h"
#include "Vmul_cone12.h"
#include "Vmul_cone16.h"
#include "Vsaturating_add_b16.h"
#include "Vsaturating_add_b4.h"
#include "Vsaturating_add_b8.h"
#include "Vsaturating_add_fault_b8.h"
#include "Vspill_register_w8.h"
#include "hls/sectoral_ism.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/kernel/hardware_configs.hpp"
#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"
#include "testbench/sectoral_ism_rtl_bench.hpp"

using namespace intgrid::kernel;

namespace intgrid::hw {
namespace {

constexpr int kTagBits = INTGRID_UNIT_TAG_W;
constexpr int kAddrBits = INTGRID_UNIT_ADDR_W;
constexpr std::int32_t kZero = IsmKernelTables::kLogZero;

std::uint64_t mask(int bits) {
  return bits >= 64 ? ~0ull : (std::uint64_t{1} << bits) - 1;
}
std::int64_t sign_extend(std::uint64_t v, int bits) {
  v &= mask(bits);
  return (v >> (bits - 1)) & 1 ? std::int64_t(v) - (std::int64_t{1} << bits) : std::int64_t(v);
}
template <class Port>
void put(Port& port, std::uint64_t v) {
  port = static_cast<Port>(v);
}

struct Config {
  const IsmHwConfig* hw;
  IsmKernelTables kernel;
  IsmHwDerived derived;
};
const Config& config(const char* name) {
  static const auto make = [](const char* n) {
    const IsmHwConfig& c = ism_hw_config(n);
    IsmKernelTables k = make_ism_hw_kernel(c);
    const IsmHwDerived d = derive_ism_hw(k, c.bits);
    return Config{&c, std::move(k), d};
  };
  static const Config cone16 = make("cone16"), cone12 = make("cone12");
  return std::string(name) == "cone16" ? cone16 : cone12;
}

// Mismatches and protocol errors of one run, the first few readable; cases counted by kind.
struct Outcome {
  std::size_t cases = 0, mismatches = 0;
  std::vector<std::pair<std::string, std::size_t>> kinds;
  std::vector<std::string> errors;
  void fail(std::uint64_t cycle, const std::string& what) {
    ++mismatches;
    if (errors.size() < 8) errors.push_back("cycle " + std::to_string(cycle) + ": " + what);
  }
  std::string summary() const {
    std::string s = std::to_string(cases) + " cases (";
    for (std::size_t i = 0; i < kinds.size(); ++i)
      s += (i ? ", " : "") + kinds[i].first + " " + std::to_string(kinds[i].second);
    s += "), " + std::to_string(mismatches) + " mismatches";
    for (const std::string& e : errors) s += "\n  " + e;
    return s;
  }
};

// A Verilated sub-module with its clock: inputs are set, eval() shows the cycle's outputs, and
// tick() is the rising edge. Registers start random (randReset(2)): only reset may clear them.
template <class Model>
class Unit {
 public:
  explicit Unit(std::uint64_t seed) : context_(std::make_unique<VerilatedContext>()) {
    context_->randReset(2);
    context_->randSeed(static_cast<int>(seed & 0x7fffffff));
    model_ = std::make_unique<Model>(context_.get());
    model_->clk_i = 0;
    model_->rst_ni = 1;
    model_->eval();
  }
  ~Unit() { model_->final(); }
  Model* operator->() { return model_.get(); }
  void tick() {
    model_->clk_i = 1;
    model_->eval();
    model_->clk_i = 0;
    model_->eval();
    ++cycle_;
  }
  std::uint64_t cycle() const { return cycle_; }

 private:
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Model> model_;
  std::uint64_t cycle_ = 0;
};

// Random traffic of a pipelined unit: a gap (valid low) with probability `gap`, a one-cycle
// reset in mid-stream with probability `reset`.
struct Traffic {
  double gap = 0.3;
  double reset = 0.0005;
};

// An operand pair of the log domain, kZero for log 0.
struct LogPair {
  std::int32_t a, b;
};

// The log word {zero, LOG_W-bit two's complement}. Log 0 carries random value bits: the units
// must look at the flag only.
std::uint64_t log_word(std::int32_t v, int log_bits, std::mt19937_64& rng) {
  if (v == kZero) return (std::uint64_t{1} << log_bits) | (rng() & mask(log_bits));
  return std::uint64_t(std::int64_t{v}) & mask(log_bits);
}
std::int32_t log_value(std::uint64_t w, int log_bits) {
  if ((w >> log_bits) & 1) return kZero;
  return static_cast<std::int32_t>(sign_extend(w, log_bits));
}

// Values at the word's limits and around zero, for pairing with log 0.
std::vector<std::int32_t> corner_values(int log_bits) {
  const std::int32_t lo = -(std::int32_t{1} << (log_bits - 1)), hi = -lo - 1;
  return {lo, lo + 1, lo + 255, -256, -1, 0, 1, 255, 256, hi - 256, hi - 1, hi};
}

// The log-0 cases of a two-operand unit: each side alone and both, with corners and random values.
void add_log_zero_cases(std::vector<LogPair>& pairs, Outcome& o, int log_bits,
                        std::mt19937_64& rng) {
  const std::int32_t lo = -(std::int32_t{1} << (log_bits - 1)), hi = -lo - 1;
  std::uniform_int_distribution<std::int32_t> any(lo, hi);
  std::vector<std::int32_t> values = corner_values(log_bits);
  for (int i = 0; i < 2000; ++i) values.push_back(any(rng));
  for (const std::int32_t x : values) pairs.push_back({kZero, x});
  o.kinds.emplace_back("log 0 left", values.size());
  for (const std::int32_t x : values) pairs.push_back({x, kZero});
  o.kinds.emplace_back("log 0 right", values.size());
  for (int i = 0; i < 500; ++i) pairs.push_back({kZero, kZero});
  o.kinds.emplace_back("log 0 both", 500);
}

// Runs `pairs` through a pipelined two-operand unit of fixed latency: `drive` sets the operand
// ports (and tag) of a case, `idle` puts garbage there, `check` compares the outputs with the
// case's expectation. The output valid must rise exactly `latency` cycles after each accepted
// case and at no other time; a reset cancels every case in flight. o.cases counts the checked
// cases (those a reset cancelled are not).
template <class Model, class Drive, class Idle, class Valid, class Check>
void run_pipeline(Unit<Model>& u, std::size_t count, int latency, const Traffic& traffic,
                  std::mt19937_64& rng, Outcome& o, Drive drive, Idle idle, Valid valid_of,
                  Check check) {
  std::bernoulli_distribution gap(traffic.gap), reset(traffic.reset);
  struct Pending {
    std::uint64_t due;
    std::size_t at;
  };
  std::deque<Pending> pending;
  for (int i = 0; i < 3; ++i) {  // reset from the random initial state
    u->rst_ni = 0;
    idle(false);
    u.tick();
  }
  u->rst_ni = 1;
  std::size_t next = 0;
  while (next < count || !pending.empty()) {
    const bool in_reset = reset(rng);
    const bool issue = next < count && !gap(rng);
    u->rst_ni = !in_reset;
    if (issue)
      drive(next);
    else
      idle(true);
    u->eval();
    const bool due = !pending.empty() && pending.front().due == u.cycle();
    if (valid_of() != due)
      o.fail(u.cycle(), due ? "no output valid when due" : "a stray output valid");
    if (due) {
      ++o.cases;
      check(pending.front().at);
      pending.pop_front();
    }
    if (in_reset)
      pending.clear();
    else if (issue)
      pending.push_back({u.cycle() + std::uint64_t(latency), next});
    if (issue) ++next;
    u.tick();
  }
}

// ------------------------------------------------------------------------------ log-add unit

std::vector<LogPair> log_add_cases(const Config& c, std::mt19937_64& rng, Outcome& o) {
  const int w = c.derived.log_bits, aw = c.derived.phi_addr_bits;
  const auto phi_n = static_cast<std::int64_t>(c.kernel.log_add.size());
  const std::int64_t lo = -(std::int64_t{1} << (w - 1)), hi = -lo - 1;
  std::vector<LogPair> pairs;
  // The sum must fit the word (the unit's contract; the kernel's values are far inside it).
  const auto fits = [&](std::int64_t a, std::int64_t b) {
    if (a < lo || a > hi || b < lo || b > hi) return false;
    const std::int32_t s = kernel_log_add(c.kernel, std::int32_t(a), std::int32_t(b));
    return s <= hi;
  };
  const auto both_orders = [&](std::int64_t low, std::int64_t d) {
    if (!fits(low, low + d)) return std::size_t{0};
    pairs.push_back({std::int32_t(low + d), std::int32_t(low)});
    pairs.push_back({std::int32_t(low), std::int32_t(low + d)});
    return std::size_t{2};
  };
  std::size_t n = 0;
  // Every distance up to twice the ROM's address range: inside the table, past its last entry,
  // past its address range.
  for (std::int64_t d = 0; d <= (std::int64_t{2} << aw) + 2; ++d) {
    std::uniform_int_distribution<std::int64_t> low(lo, hi - d - 256);
    n += both_orders(low(rng), d);
  }
  o.kinds.emplace_back("every distance 0.." + std::to_string((2 << aw) + 2), n);
  // Distances whose low address bits fall inside the table: Phi must still be 0.
  n = 0;
  for (std::int64_t m = 1; (m << aw) <= hi - lo; ++m)
    for (const std::int64_t j : {std::int64_t{0}, std::int64_t{1}, phi_n - 1, phi_n}) {
      const std::int64_t d = (m << aw) + j;
      if (d > hi - lo) continue;
      std::uniform_int_distribution<std::int64_t> low(lo, hi - d);
      n += both_orders(low(rng), d);
    }
  o.kinds.emplace_back("aliasing distances", n);
  // The word's limits.
  n = 0;
  for (const std::int64_t a : {lo, lo + 1, hi - 256, hi - 1, hi})
    for (const std::int64_t b : {lo, lo + 1, lo + phi_n, hi - phi_n, hi - 256, hi - 1, hi})
      if (fits(a, b)) {
        pairs.push_back({std::int32_t(a), std::int32_t(b)});
        ++n;
      }
  o.kinds.emplace_back("word limits", n);
  // Random pairs: anywhere, and close (distance inside the table).
  n = 0;
  std::uniform_int_distribution<std::int64_t> any(lo, hi), close(-2 * phi_n, 2 * phi_n);
  while (n < 100000) {
    const std::int64_t a = any(rng), b = n % 2 ? any(rng) : a + close(rng);
    if (fits(a, b)) {
      pairs.push_back({std::int32_t(a), std::int32_t(b)});
      ++n;
    }
  }
  o.kinds.emplace_back("random", n);
  add_log_zero_cases(pairs, o, w, rng);
  return pairs;
}

template <class Model>
Outcome check_log_add(const Config& c, std::vector<LogPair> pairs, std::uint64_t seed,
                      Outcome o = {}) {
  std::mt19937_64 rng(seed);
  std::shuffle(pairs.begin(), pairs.end(), rng);
  const int w = c.derived.log_bits;
  Unit<Model> u(seed);
  std::vector<std::uint32_t> tags(pairs.size());
  for (auto& t : tags) t = static_cast<std::uint32_t>(rng() & mask(kTagBits));
  run_pipeline(
      u, pairs.size(), 2, Traffic{}, rng, o,
      [&](std::size_t i) {
        u->valid_i = 1;
        put(u->a_i, log_word(pairs[i].a, w, rng));
        put(u->b_i, log_word(pairs[i].b, w, rng));
        put(u->tag_i, tags[i]);
      },
      [&](bool garbage) {
        u->valid_i = 0;
        put(u->a_i, garbage ? rng() : 0);
        put(u->b_i, garbage ? rng() : 0);
        put(u->tag_i, garbage ? rng() : 0);
      },
      [&] { return u->valid_o != 0; },
      [&](std::size_t i) {
        const std::int32_t want = kernel_log_add(c.kernel, pairs[i].a, pairs[i].b);
        const std::int32_t got = log_value(u->res_o, w);
        if (got != want || u->tag_o != tags[i])
          o.fail(u.cycle(), "log_add(" + std::to_string(pairs[i].a) + ", " +
                                std::to_string(pairs[i].b) + ") = " + std::to_string(got) +
                                " tag " + std::to_string(u->tag_o) + ", golden " +
                                std::to_string(want) + " tag " + std::to_string(tags[i]));
      });
  return o;
}

template <class Model>
Outcome test_log_add(const char* name, std::uint64_t default_seed) {
  const Config& c = config(name);
  const std::uint64_t seed = ism_bench_seed(default_seed, (std::string("log_add ") + name).c_str());
  std::mt19937_64 rng(seed);
  Outcome o;
  std::vector<LogPair> pairs = log_add_cases(c, rng, o);
  return check_log_add<Model>(c, std::move(pairs), rng(), std::move(o));
}

// ---------------------------------------------------------------------------------- index unit

std::vector<LogPair> index_cases(const Config& c, std::mt19937_64& rng, Outcome& o) {
  const int w = c.derived.log_bits;
  const std::int64_t lo = -(std::int64_t{1} << (w - 1)), hi = -lo - 1;
  std::vector<LogPair> pairs;
  // odds = num - den with den drawn so that both fit the word.
  const auto with_odds = [&](std::int64_t odds) {
    std::uniform_int_distribution<std::int64_t> den(std::max(lo, lo - odds),
                                                    std::min(hi, hi - odds));
    const std::int64_t d = den(rng);
    pairs.push_back({std::int32_t(d + odds), std::int32_t(d)});
  };
  // Every magnitude up to two buckets past the last threshold, both signs.
  const std::int64_t top = std::int64_t(c.derived.bucket_count + 2) << c.derived.bucket_shift;
  for (std::int64_t m = 0; m <= top; ++m) {
    with_odds(m);
    if (m) with_odds(-m);
  }
  o.kinds.emplace_back("every |odds| 0.." + std::to_string(top) + " (every threshold +-1)",
                       std::size_t(2 * top + 1));
  // Every threshold and its neighbours once more, at the word's limits of num and den.
  std::size_t n = 0;
  for (const std::int32_t t : c.kernel.thresholds)
    for (const std::int64_t m : {std::int64_t{t} - 1, std::int64_t{t}, std::int64_t{t} + 1}) {
      pairs.push_back({std::int32_t(hi), std::int32_t(hi - m)});  // odds m at the top
      pairs.push_back({std::int32_t(lo), std::int32_t(lo + m)});  // odds -m at the bottom
      n += 2;
    }
  o.kinds.emplace_back("thresholds +-1 at the limits", n);
  // The widest odds.
  n = 0;
  for (const std::int64_t a : {lo, lo + 1, std::int64_t{0}, hi - 1, hi})
    for (const std::int64_t b : {lo, lo + 1, std::int64_t{0}, hi - 1, hi}) {
      pairs.push_back({std::int32_t(a), std::int32_t(b)});
      ++n;
    }
  o.kinds.emplace_back("word limits", n);
  std::uniform_int_distribution<std::int64_t> any(lo, hi);
  for (int i = 0; i < 50000; ++i) pairs.push_back({std::int32_t(any(rng)), std::int32_t(any(rng))});
  o.kinds.emplace_back("random", 50000);
  add_log_zero_cases(pairs, o, w, rng);
  return pairs;
}

template <class Model>
Outcome check_index(const Config& c, std::vector<LogPair> pairs, std::uint64_t seed,
                    Outcome o = {}) {
  std::mt19937_64 rng(seed);
  std::shuffle(pairs.begin(), pairs.end(), rng);
  const int w = c.derived.log_bits, idx_bits = c.derived.index_bits;
  Unit<Model> u(seed);
  std::vector<std::uint32_t> addr(pairs.size());
  for (auto& a : addr) a = static_cast<std::uint32_t>(rng() & mask(kAddrBits));
  run_pipeline(
      u, pairs.size(), 3, Traffic{}, rng, o,
      [&](std::size_t i) {
        u->valid_i = 1;
        put(u->num_i, log_word(pairs[i].a, w, rng));
        put(u->den_i, log_word(pairs[i].b, w, rng));
        put(u->waddr_i, addr[i]);
      },
      [&](bool garbage) {
        u->valid_i = 0;
        put(u->num_i, garbage ? rng() : 0);
        put(u->den_i, garbage ? rng() : 0);
        put(u->waddr_i, garbage ? rng() : 0);
      },
      [&] { return u->we_o != 0; },
      [&](std::size_t i) {
        const int want = kernel_index_of_log_odds(c.kernel, pairs[i].a, pairs[i].b);
        const auto got = static_cast<int>(sign_extend(u->wdata_o, idx_bits));
        if (got != want || u->waddr_o != addr[i])
          o.fail(u.cycle(), "index(" + std::to_string(pairs[i].a) + ", " +
                                std::to_string(pairs[i].b) + ") = " + std::to_string(got) + " at " +
                                std::to_string(u->waddr_o) + ", golden " + std::to_string(want) +
                                " at " + std::to_string(addr[i]));
      });
  return o;
}

template <class Model>
Outcome test_index(const char* name, std::uint64_t default_seed) {
  const Config& c = config(name);
  const std::uint64_t seed = ism_bench_seed(default_seed, (std::string("index ") + name).c_str());
  std::mt19937_64 rng(seed);
  Outcome o;
  std::vector<LogPair> pairs = index_cases(c, rng, o);
  return check_index<Model>(c, std::move(pairs), rng(), std::move(o));
}

// ---------------------------------------------------------------------------------- multiplier

struct MulShape {
  int a_bits, b_bits, digit_bits;
  int digits() const { return (b_bits + digit_bits - 1) / digit_bits; }
};

// A product started in cycle s is due with done_o in cycle s + ND + 2; starts come at least ND
// cycles apart, often exactly ND (the previous product's last digit).
template <class Model>
Outcome check_mul(const MulShape& shape,
                  const std::vector<std::pair<std::uint64_t, std::uint64_t>>& ops,
                  std::uint64_t seed, Outcome o = {}) {
  std::mt19937_64 rng(seed);
  Unit<Model> u(seed);
  const int nd = shape.digits();
  std::vector<std::uint32_t> tags(ops.size());
  for (auto& t : tags) t = static_cast<std::uint32_t>(rng() & mask(kTagBits));
  std::uniform_int_distribution<int> extra(0, 3);
  std::bernoulli_distribution back_to_back(0.5);
  int wait = 0;  // cycles until the next start is allowed
  std::bernoulli_distribution reset(0.0005);
  struct Pending {
    std::uint64_t due;
    std::size_t at;
  };
  std::deque<Pending> pending;
  for (int i = 0; i < 3; ++i) {
    u->rst_ni = 0;
    u->start_i = 0;
    u.tick();
  }
  u->rst_ni = 1;
  std::size_t next = 0;
  while (next < ops.size() || !pending.empty()) {
    const bool in_reset = reset(rng);
    const bool start = next < ops.size() && wait <= 0;
    u->rst_ni = !in_reset;
    u->start_i = start;
    put(u->a_i, start ? ops[next].first : rng());
    put(u->b_i, start ? ops[next].second : rng());
    put(u->tag_i, start ? tags[next] : rng());
    u->eval();
    const bool due = !pending.empty() && pending.front().due == u.cycle();
    if ((u->done_o != 0) != due) o.fail(u.cycle(), due ? "no done_o when due" : "a stray done_o");
    if (due) {
      ++o.cases;
      const auto [a, b] = ops[pending.front().at];
      const std::uint64_t got = u->p_o;
      if (got != a * b || u->tag_o != tags[pending.front().at])
        o.fail(u.cycle(), std::to_string(a) + " * " + std::to_string(b) + " = " +
                              std::to_string(got) + " tag " + std::to_string(u->tag_o));
      pending.pop_front();
    }
    if (in_reset) {
      pending.clear();
      wait = 0;  // the reset idles the multiplier
    } else if (start) {
      pending.push_back({u.cycle() + std::uint64_t(nd + 2), next});
      wait = nd + (back_to_back(rng) ? 0 : extra(rng));
    }
    if (start) ++next;
    --wait;
    u.tick();
  }
  return o;
}

std::vector<std::pair<std::uint64_t, std::uint64_t>> mul_cases(const MulShape& s,
                                                               std::mt19937_64& rng, Outcome& o) {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> ops;
  if (s.a_bits + s.b_bits <= 14) {
    for (std::uint64_t a = 0; a <= mask(s.a_bits); ++a)
      for (std::uint64_t b = 0; b <= mask(s.b_bits); ++b) ops.emplace_back(a, b);
    o.kinds.emplace_back("every pair", ops.size());
    return ops;
  }
  const auto corners = [](int bits) {
    std::vector<std::uint64_t> v{0,
                                 1,
                                 2,
                                 3,
                                 mask(bits),
                                 mask(bits) - 1,
                                 0x5555555555555555ull & mask(bits),
                                 0xaaaaaaaaaaaaaaaaull & mask(bits)};
    for (int i = 1; i < bits; ++i) {
      v.push_back(std::uint64_t{1} << i);
      v.push_back((std::uint64_t{1} << i) - 1);
    }
    return v;
  };
  for (const std::uint64_t a : corners(s.a_bits))
    for (const std::uint64_t b : corners(s.b_bits)) ops.emplace_back(a, b);
  o.kinds.emplace_back("corners x corners", ops.size());
  for (int i = 0; i < 20000; ++i) ops.emplace_back(rng() & mask(s.a_bits), rng() & mask(s.b_bits));
  o.kinds.emplace_back("random", 20000);
  std::shuffle(ops.begin(), ops.end(), rng);
  return ops;
}

template <class Model>
Outcome test_mul(const MulShape& s, const std::string& what, std::uint64_t default_seed) {
  const std::uint64_t seed = ism_bench_seed(default_seed, ("mul " + what).c_str());
  std::mt19937_64 rng(seed);
  Outcome kinds;
  const auto ops = mul_cases(s, rng, kinds);
  Outcome o = check_mul<Model>(s, ops, rng());
  o.kinds = kinds.kinds;
  return o;
}

MulShape mul_shape_of(const Config& c) {
  return {c.derived.sq_bits, c.derived.mul_b_bits, c.derived.mul_digit_bits};
}

// --------------------------------------------------------------------------------- density unit

// The rings r with |z - r U| < window U, i.e. those the unit computes for reading z.
std::pair<int, int> window_rings(const IsmKernelTables& k, std::uint32_t z) {
  const std::int64_t unit = std::int64_t{1} << k.format.reading_frac_bits;
  int lo = 0, hi = -1;
  for (int r = 1; r <= k.grid.rings; ++r) {
    const std::int64_t e = std::int64_t{z} - r * unit;
    if ((e < 0 ? -e : e) < k.window_cells * unit) {
      if (!lo) lo = r;
      hi = r;
    }
  }
  return {lo, hi};
}

// Drives the unit as the set-up engine does, per reading: init with e = z - r_lo U and the ROM
// base of r_lo; ND + 1 idle cycles or more; then n + 1 slots (n rings in the window), the first n
// computing the next ring and advancing in their last cycle. Slots last C ND + 5 cycles (the
// least the unit needs: its last density is stored in slot cycle C ND + 4) or randomly longer,
// up to the engine's V C. In every cycle of slot k >= 1, dens_o for a random class must be ring
// r_lo + k - 1's density (in slot cycle 0 still ring r_lo + k - 2's), and all classes are read
// in slot cycle 1. run_i outside slot_i and the e/base ports outside init_i carry garbage.
template <class Model, class Cfg>
Outcome check_density(const Config& c, const std::vector<std::uint32_t>& readings,
                      std::uint64_t seed) {
  const IsmKernelTables& k = c.kernel;
  const int C = k.classes, nd = c.derived.mul_digits, w = c.derived.log_bits;
  const int slot_min = C * nd + 5, slot_max = std::max(slot_min, k.conditions * C);
  const std::int64_t unit = std::int64_t{1} << k.format.reading_frac_bits;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> cls(0, C - 1), idle(0, 3), slot_len(slot_min, slot_max);
  std::bernoulli_distribution shortest(0.6);
  Unit<Model> u(seed);
  Outcome o;
  o.cases = 0;
  const auto inputs = [&](bool init, bool slot, bool run, bool advance) {
    u->init_i = init;
    u->slot_i = slot;
    u->run_i = slot ? run : (rng() & 1);
    u->advance_i = advance;
    if (!init) {
      put(u->e_i, rng());
      put(u->base_i, rng());
    }
    put(u->cls_i, std::uint64_t(cls(rng)));
  };
  const auto expect = [&](std::uint32_t z, int ring, int cl) {
    const std::int32_t want = hls::ism_log_density<Cfg>(z, ring, cl);
    put(u->cls_i, std::uint64_t(cl));
    u->eval();
    const auto got = static_cast<std::int32_t>(sign_extend(u->dens_o, w));
    if (got != want)
      o.fail(u.cycle(), "density(z " + std::to_string(z) + ", ring " + std::to_string(ring) +
                            ", class " + std::to_string(cl) + ") = " + std::to_string(got) +
                            ", hls " + std::to_string(want));
  };
  u->rst_ni = 0;
  inputs(false, false, false, false);
  for (int i = 0; i < 3; ++i) u.tick();
  u->rst_ni = 1;
  std::size_t rings = 0;
  for (const std::uint32_t z : readings) {
    const auto [r_lo, r_hi] = window_rings(k, z);
    if (!r_lo) continue;
    const int n = r_hi - r_lo + 1;
    for (int i = idle(rng); i > 0; --i) {
      inputs(false, false, false, false);
      u.tick();
    }
    inputs(true, false, false, false);
    put(u->e_i, std::uint64_t(std::int64_t{z} - r_lo * unit));
    put(u->base_i, std::uint64_t((r_lo - 1) * C));
    u.tick();
    for (int i = nd + 1 + idle(rng); i > 0; --i) {
      inputs(false, false, false, false);
      u.tick();
    }
    for (int slot = 0; slot <= n; ++slot) {
      const int len = shortest(rng) ? slot_min : slot_len(rng);
      for (int t = 0; t < len; ++t) {
        inputs(false, t == 0, slot < n, slot < n && t == len - 1);
        u->eval();
        if (t == 0 && slot >= 2) expect(z, r_lo + slot - 2, cls(rng));
        if (t == 1 && slot >= 1)
          for (int cl = 0; cl < C; ++cl) expect(z, r_lo + slot - 1, cl);
        if (t > 1 && slot >= 1) expect(z, r_lo + slot - 1, cls(rng));
        u.tick();
      }
    }
    rings += std::size_t(n);
    o.cases += std::size_t(n * C);
  }
  o.kinds.emplace_back("readings", readings.size());
  o.kinds.emplace_back("(reading, ring) pairs", rings);
  return o;
}

template <class Model, class Cfg>
Outcome test_density(std::uint64_t default_seed) {
  const Config& c = config(Cfg::name);
  const std::uint64_t seed =
      ism_bench_seed(default_seed, (std::string("density ") + Cfg::name).c_str());
  std::vector<std::uint32_t> z(c.kernel.reach);  // every reading that informs a ring
  for (std::uint32_t i = 0; i < c.kernel.reach; ++i) z[i] = i;
  std::shuffle(z.begin(), z.end(), std::mt19937_64(seed));
  return check_density<Model, Cfg>(c, z, seed + 1);
}

// -------------------------------------------------------------------- shared: spill register

// Against a two-entry FIFO: valid_o = not empty, ready_o = fewer than two, data_o = the oldest;
// outputs depend on registers only (changing the inputs within a cycle changes nothing). The
// source keeps its beat while valid && !ready. Phases of traffic, and rare resets that empty it.
Outcome check_spill_register(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Unit<Vspill_register_w8> u(seed);
  std::deque<std::uint8_t> fifo;
  Outcome o;
  u->rst_ni = 0;
  u->valid_i = 0;
  u->ready_i = 0;
  for (int i = 0; i < 3; ++i) u.tick();
  u->rst_ni = 1;
  const double rates[][2] = {{1.0, 1.0}, {0.5, 1.0}, {1.0, 0.5},
                             {0.9, 0.3}, {0.3, 0.9}, {0.6, 0.6}};
  bool offering = false;
  std::uint8_t beat = 0;
  std::size_t moved_full_rate = 0;
  for (const auto& rate : rates) {
    std::bernoulli_distribution valid(rate[0]), ready(rate[1]), reset(0.002);
    for (int cycle = 0; cycle < 20000; ++cycle) {
      const bool in_reset = rate[0] < 1.0 && reset(rng);
      if (!offering && valid(rng)) {
        offering = true;
        beat = static_cast<std::uint8_t>(rng());
      }
      u->rst_ni = !in_reset;
      u->valid_i = offering;
      u->data_i = offering ? beat : static_cast<std::uint8_t>(rng());
      u->ready_i = ready(rng);
      u->eval();
      const bool v = u->valid_o, r = u->ready_o;
      const std::uint8_t d = u->data_o;
      if (v != !fifo.empty() || r != (fifo.size() < 2) || (v && d != fifo.front()))
        o.fail(u.cycle(), "valid/ready/data " + std::to_string(v) + "/" + std::to_string(r) + "/" +
                              std::to_string(d) + " with " + std::to_string(fifo.size()) +
                              " beats held");
      const auto saved_valid = u->valid_i, saved_ready = u->ready_i;
      u->valid_i = !saved_valid;
      u->ready_i = !saved_ready;
      u->data_i = static_cast<std::uint8_t>(~u->data_i);
      u->eval();
      if (u->valid_o != v || u->ready_o != r || u->data_o != d)
        o.fail(u.cycle(), "an output follows an input in the same cycle");
      u->valid_i = saved_valid;
      u->ready_i = saved_ready;
      u->data_i = static_cast<std::uint8_t>(~u->data_i);
      u->eval();
      const bool in = u->valid_i && r, out = v && u->ready_i;
      ++o.cases;
      u.tick();
      if (in_reset) {
        fifo.clear();
        offering = false;
        continue;
      }
      if (out) fifo.pop_front();
      if (in) {
        fifo.push_back(beat);
        offering = false;
      }
      if (rate[0] == 1.0 && rate[1] == 1.0 && out) ++moved_full_rate;
    }
  }
  if (moved_full_rate + 1 < 20000) o.fail(u.cycle(), "fewer than one beat a cycle at full rate");
  o.kinds.emplace_back("cycles", o.cases);
  return o;
}

// ----------------------------------------------------------------- shared: saturating adder

template <class Model, int B>
Outcome check_saturating_add(std::uint64_t seed) {
  const int max_index = (1 << (B - 1)) - 1;
  const std::int64_t lo = -(std::int64_t{1} << (B - 1)), hi = max_index;
  VerilatedContext context;  // its own: the default one may be a destroyed unit's
  Model m(&context);
  Outcome o;
  const auto one = [&](std::int64_t a, std::int64_t b) {
    put(m.a_i, std::uint64_t(a) & mask(B));
    put(m.b_i, std::uint64_t(b) & mask(B));
    m.eval();
    const auto got = sign_extend(m.y_o, B);
    const int want = core::fuse_indices(int(a), int(b), max_index);
    ++o.cases;
    if (got != want)
      o.fail(0, std::to_string(a) + " + " + std::to_string(b) + " = " + std::to_string(got) +
                    ", golden " + std::to_string(want));
  };
  if (2 * B <= 20) {
    for (std::int64_t a = lo; a <= hi; ++a)
      for (std::int64_t b = lo; b <= hi; ++b) one(a, b);
    o.kinds.emplace_back("every pair", o.cases);
  } else {
    const std::vector<std::int64_t> corners{lo, lo + 1, lo + 2, -2,     -1, 0,
                                            1,  2,      hi - 2, hi - 1, hi};
    for (const auto a : corners)
      for (const auto b : corners) one(a, b);
    o.kinds.emplace_back("corners x corners", o.cases);
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<std::int64_t> any(lo, hi);
    for (int i = 0; i < (1 << 18); ++i) one(any(rng), any(rng));
    o.kinds.emplace_back("random", std::size_t{1} << 18);
  }
  m.final();
  return o;
}

void report(const char* what, const Outcome& o) {
  std::printf("[%s] %s\n", what, o.summary().c_str());
}

// ------------------------------------------------------------------------------------- tests

TEST(IsmUnits, LogAddCone16) {
  const Outcome o = test_log_add<Vlog_add_cone16>("cone16", 11);
  report("log_add cone16", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, LogAddCone12) {
  const Outcome o = test_log_add<Vlog_add_cone12>("cone12", 12);
  report("log_add cone12", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, IndexCone16) {
  const Outcome o = test_index<Vindex_cone16>("cone16", 21);
  report("index cone16", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, IndexCone12) {
  const Outcome o = test_index<Vindex_cone12>("cone12", 22);
  report("index cone12", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, DensityCone16) {
  const Outcome o = test_density<Vdensity_cone16, SectoralIsmCone16>(31);
  report("density cone16", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, DensityCone12) {
  const Outcome o = test_density<Vdensity_cone12, SectoralIsmCone12>(32);
  report("density cone12", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, MulCone16) {
  const Outcome o = test_mul<Vmul_cone16>(mul_shape_of(config("cone16")), "cone16", 41);
  report("mul cone16", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, MulCone12) {
  const Outcome o = test_mul<Vmul_cone12>(mul_shape_of(config("cone12")), "cone12", 42);
  report("mul cone12", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, MulEveryPairSmallShapes) {
  const Outcome a = test_mul<Vmul_a6_b5_k2>({6, 5, 2}, "6x5, 2 bits a digit", 43);
  const Outcome b = test_mul<Vmul_a5_b7_k7>({5, 7, 7}, "5x7, one digit", 44);
  const Outcome c = test_mul<Vmul_a4_b6_k1>({4, 6, 1}, "4x6, 1 bit a digit", 45);
  report("mul 6x5 k2", a);
  report("mul 5x7 k7", b);
  report("mul 4x6 k1", c);
  EXPECT_EQ(a.mismatches + b.mismatches + c.mismatches, 0u) << a.summary() << "\n"
                                                            << b.summary() << "\n"
                                                            << c.summary();
}
TEST(IsmUnits, SpillRegister) {
  const Outcome o = check_spill_register(ism_bench_seed(51, "spill_register"));
  report("spill_register", o);
  EXPECT_EQ(o.mismatches, 0u) << o.summary();
}
TEST(IsmUnits, SaturatingAdd) {
  const std::uint64_t seed = ism_bench_seed(52, "saturating_add");
  const Outcome b4 = check_saturating_add<Vsaturating_add_b4, 4>(seed);
  const Outcome b8 = check_saturating_add<Vsaturating_add_b8, 8>(seed);
  const Outcome b16 = check_saturating_add<Vsaturating_add_b16, 16>(seed);
  report("saturating_add B 4", b4);
  report("saturating_add B 8", b8);
  report("saturating_add B 16", b16);
  EXPECT_EQ(b4.mismatches + b8.mismatches + b16.mismatches, 0u) << b4.summary() << "\n"
                                                                << b8.summary() << "\n"
                                                                << b16.summary();
}

// Each fault must be caught by the same check as the intact unit (cone16).
TEST(IsmUnitsFault, LogAddBothZero) {
  const Outcome o = test_log_add<Vlog_add_fault_both_zero>("cone16", 11);
  report("log_add fault both_zero", o);
  EXPECT_GT(o.mismatches, 0u);
}
TEST(IsmUnitsFault, LogAddPassA) {
  const Outcome o = test_log_add<Vlog_add_fault_pass_a>("cone16", 11);
  report("log_add fault pass_a", o);
  EXPECT_GT(o.mismatches, 0u);
}
TEST(IsmUnitsFault, IndexDenZero) {
  const Outcome o = test_index<Vindex_fault_den_zero>("cone16", 21);
  report("index fault den_zero", o);
  EXPECT_GT(o.mismatches, 0u);
}
TEST(IsmUnitsFault, IndexNumZero) {
  const Outcome o = test_index<Vindex_fault_num_zero>("cone16", 21);
  report("index fault num_zero", o);
  EXPECT_GT(o.mismatches, 0u);
}
TEST(IsmUnitsFault, IndexBothZero) {
  const Outcome o = test_index<Vindex_fault_both_zero>("cone16", 21);
  report("index fault both_zero", o);
  EXPECT_GT(o.mismatches, 0u);
}
TEST(IsmUnitsFault, SaturatingAdd) {
  const Outcome o = check_saturating_add<Vsaturating_add_fault_b8, 8>(52);
  report("saturating_add fault", o);
  EXPECT_GT(o.mismatches, 0u);
}

}  // namespace
}  // namespace intgrid::hw
