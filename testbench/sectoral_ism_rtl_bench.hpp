// A Verilator C++ bench of the sectoral ISM RTL (top `sectoral_ism`, one Verilated model
// per configuration): drives readings with random input gaps against random output
// back-pressure and checks, cycle by cycle,
//   - every output beat against golden's ism_kernel_indices of the reading it belongs to,
//     in order, with y_last exactly on each reading's last cell (no drop, no duplicate);
//   - y_valid, y_data and y_last stable while y_valid && !y_ready;
//   - nothing comes out that was not asked for, and everything asked for comes out;
//   - no RTL assertion fails (the models are verilated with --assert; a failure ends the run);
//   - given the schedule (IsmBenchOptions::setup_cycles), no ready cycle is wasted: y_valid is
//     low while y_ready is high only before the next reading's bank can have reached y
//     (accepted at a, set-up s cycles: its first cell can leave from cycle a + s + 3 on).
// It measures set-up cycles (reading accepted -> z_ready again, idle kernel), latency
// (reading accepted -> its first cell valid) and total cycles, and hashes what the ports show
// every cycle (to compare a run after a reset with one from power-up).
#pragma once

#include <verilated.h>
#if VM_TRACE
#include <verilated_fst_c.h>
#endif

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "intgrid/kernel/ism_kernel.hpp"
#include "testbench/verilated_thread_context.hpp"

namespace intgrid::hw {

// The seed of a randomized run: INTGRID_ISM_SEED if set, else `fallback`; printed.
inline std::uint64_t ism_bench_seed(std::uint64_t fallback, const char* what) {
  std::uint64_t seed = fallback;
  if (const char* env = std::getenv("INTGRID_ISM_SEED")) seed = std::strtoull(env, nullptr, 0);
  std::printf("[%s] seed %llu (set INTGRID_ISM_SEED to replay)\n", what,
              static_cast<unsigned long long>(seed));
  return seed;
}

// The readings every run includes: z = 0, below the first ring, on and between every ring,
// at and past the last ring, at and past reach, and the largest reading the port holds.
inline std::vector<std::uint32_t> ism_edge_readings(const kernel::IsmKernelTables& k,
                                                    int reading_bits) {
  const std::uint32_t unit = 1u << k.format.reading_frac_bits;
  std::vector<std::uint32_t> out{0, 1, unit / 2, unit - 1};
  for (int r = 1; r <= k.grid.rings; ++r) {
    out.push_back(std::uint32_t(r) * unit - 1);
    out.push_back(std::uint32_t(r) * unit);
    out.push_back(std::uint32_t(r) * unit + 1);
    out.push_back(std::uint32_t(r) * unit + unit / 2);
  }
  const std::uint32_t last = std::uint32_t(k.grid.rings) * unit;
  for (const std::uint32_t z : {last + unit, last + 2 * unit, k.reach - 1, k.reach, k.reach + 1,
                                k.reach + unit, (1u << reading_bits) - 1})
    out.push_back(z);
  return out;
}

// `count` random readings: most over [0, reach + one cell], some over the whole port.
inline std::vector<std::uint32_t> ism_random_readings(const kernel::IsmKernelTables& k,
                                                      int reading_bits, std::size_t count,
                                                      std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::uint32_t unit = 1u << k.format.reading_frac_bits;
  std::uniform_int_distribution<std::uint32_t> near(0, k.reach + unit);
  std::uniform_int_distribution<std::uint32_t> any(0, (1u << reading_bits) - 1);
  std::uniform_int_distribution<int> pick(0, 15);
  std::vector<std::uint32_t> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(pick(rng) == 0 ? any(rng) : near(rng));
  return out;
}

struct IsmBenchOptions {
  std::uint64_t seed = 1;
  double gap = 0.3;       // probability of holding z_valid low a cycle before offering a reading
  double ready = 0.7;     // probability of y_ready each cycle (1 = no back-pressure)
  bool isolated = false;  // offer a reading only when the kernel has sent everything before
  // If not 0: offer a reading only once at most this many cells of the earlier ones are unsent.
  std::size_t offer_at_unsent = 0;
  bool stop_at_first_error = false;
  std::uint64_t max_idle_cycles = 100000;  // fail if nothing moves this long
  // Leave the run after this many cycles, whatever is in flight (to reset in mid-stream).
  std::uint64_t stop_after_cycles = UINT64_MAX;
  // The set-up cycles of a reading (sc::sectoral_ism_setup_cycles<Config>): enables the
  // wasted-ready-cycle check.
  std::uint64_t (*setup_cycles)(std::uint32_t) = nullptr;
};

struct IsmBenchResult {
  std::size_t readings = 0, cells = 0;
  std::size_t mismatches = 0, protocol_errors = 0;
  std::size_t assertion_failures = 0;    // cycles in which an RTL assertion failed
  std::size_t wasted_cycles = 0;         // y_ready && !y_valid with a cell that could have left
  std::uint64_t idle_output_cycles = 0;  // y_valid low between the first and the last cell
  std::uint64_t port_hash = 0;           // of every cycle's z_ready, y_valid (y_data, y_last)
  bool stopped = false;                  // left at stop_after_cycles
  std::uint64_t cycles = 0;
  double host_seconds = 0.0;
  std::vector<std::uint64_t> setup_cycles;   // per reading (isolated runs)
  std::vector<std::uint64_t> latencies;      // per reading: accepted -> first cell valid
  std::vector<std::uint64_t> accept_cycles;  // per reading accepted
  std::vector<std::uint64_t> first_cells;    // per reading: the cycle its first cell left
  std::vector<std::string> errors;           // the first few, readable
  bool ok() const {
    return mismatches == 0 && protocol_errors == 0 && assertion_failures == 0 &&
           wasted_cycles == 0 && errors.empty();
  }
  std::string summary() const {
    std::ostringstream s;
    s << readings << " readings, " << cells << " cells, " << cycles << " cycles, " << mismatches
      << " mismatching cells, " << protocol_errors << " protocol errors, " << assertion_failures
      << " assertion failures, " << wasted_cycles << " wasted ready cycles";
    for (const std::string& e : errors) s << "\n  " << e;
    return s.str();
  }
};

template <class Model>
class IsmRtlBench {
 public:
  // trace_path: an FST file to dump (needs a model verilated with TRACE_FST), or empty.
  // init_seed: negative for an all-zero initial state, else the seed of a random one (the
  // models are verilated with --x-initial unique).
  IsmRtlBench(const kernel::IsmKernelTables& kernel, const std::string& trace_path = {},
              int init_seed = -1)
      : kernel_(kernel), context_(std::make_unique<VerilatedContext>()) {
    context_->randReset(init_seed < 0 ? 0 : 2);
    if (init_seed >= 0) context_->randSeed(init_seed);
    context_->fatalOnError(false);  // a failed assertion is counted by the bench, not aborted
    tb::use_verilated_context(context_.get());  // while its model is built (see the function)
    model_ = std::make_unique<Model>(context_.get());
    model_->clk_i = 0;
#if VM_TRACE
    if (!trace_path.empty()) {
      context_->traceEverOn(true);
      trace_ = std::make_unique<VerilatedFstC>();
      model_->trace(trace_.get(), 99);
      trace_->open(trace_path.c_str());
    }
#else
    (void)trace_path;
#endif
    reset(4);
  }
  ~IsmRtlBench() {
#if VM_TRACE
    if (trace_) trace_->close();
#endif
    tb::use_verilated_context(context_.get());
    model_->final();
    model_.reset();
  }

  IsmBenchResult run(std::span<const std::uint32_t> readings, const IsmBenchOptions& opt) {
    IsmBenchResult res;
    std::mt19937_64 rng(opt.seed);
    std::bernoulli_distribution gap(opt.gap), ready(opt.ready);
    const std::size_t cells_per_reading = kernel_.grid.cells();
    const int index_bits = index_bits_of(kernel_.max_index);
    std::deque<std::vector<std::int16_t>> expected;  // accepted readings not yet sent
    std::deque<std::uint64_t> accepted_at;           // their accept cycles (latency)
    std::size_t next = 0, out_cell = 0;
    bool offering = false, prev_stall = false, seen_first = false;
    std::uint8_t prev_last = 0;
    std::uint32_t prev_data = 0;
    std::uint64_t idle = 0, setup_start = 0, idle_output = 0;
    bool timing_setup = false;
    std::uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a over the ports, cycle by cycle
    const auto mix = [&](std::uint64_t v) { hash = (hash ^ v) * 0x100000001b3ull; };
    const auto error = [&](const std::string& e) {
      if (res.errors.size() < 8)
        res.errors.push_back("cycle " + std::to_string(res.cycles) + ": " + e);
    };
    const auto t0 = std::chrono::steady_clock::now();
    while (next < readings.size() || !expected.empty()) {
      if (res.cycles >= opt.stop_after_cycles) {
        res.stopped = true;
        break;
      }
      // Inputs for this cycle.
      if (!offering && next < readings.size()) {
        const bool drained = expected.empty() && !timing_setup;
        const std::size_t unsent = expected.size() * cells_per_reading - out_cell;
        const bool late = opt.offer_at_unsent == 0 || unsent <= opt.offer_at_unsent;
        if ((!opt.isolated || drained) && late && !gap(rng)) offering = true;
      }
      model_->z_valid_i = offering;
      using ZData = std::remove_reference_t<decltype(model_->z_data_i)>;
      model_->z_data_i = static_cast<ZData>(offering ? readings[next] : 0xdeadu);
      model_->z_last_i = offering;
      const bool y_ready = ready(rng);
      model_->y_ready_i = y_ready;
      model_->eval();
      // Outputs of this cycle.
      const bool z_fire = model_->z_valid_i && model_->z_ready_o;
      const bool y_valid = model_->y_valid_o;
      const std::uint32_t y_data = model_->y_data_o;
      const std::uint8_t y_last = model_->y_last_o;
      mix(std::uint64_t{model_->z_ready_o} | std::uint64_t{y_valid} << 1 |
          (y_valid ? (std::uint64_t{y_last} << 2 | std::uint64_t{y_data} << 3) : 0));
      if (y_valid && !res.first_cells.empty()) res.idle_output_cycles += idle_output;
      if (y_valid) idle_output = 0;
      if (!y_valid && (!res.first_cells.empty())) ++idle_output;
      if (opt.setup_cycles && y_ready && !y_valid && !expected.empty()) {
        // The next cell is cell out_cell of the oldest pending reading.
        const std::size_t i = res.readings;
        const std::uint64_t earliest = res.accept_cycles[i] + opt.setup_cycles(readings[i]) + 3;
        if (out_cell > 0 || res.cycles >= earliest) {
          ++res.wasted_cycles;
          error("y_ready wasted: reading " + std::to_string(i) + " cell " +
                std::to_string(out_cell) + " could have left from cycle " +
                std::to_string(earliest));
        }
      }
      if (prev_stall && (!y_valid || y_data != prev_data || y_last != prev_last)) {
        ++res.protocol_errors;
        error("output changed while valid && !ready");
      }
      prev_stall = y_valid && !y_ready;
      prev_data = y_data;
      prev_last = y_last;
      if (timing_setup && model_->z_ready_o) {  // the engine is idle again
        res.setup_cycles.push_back(res.cycles - setup_start - 1);
        timing_setup = false;
      }
      if (z_fire) {
        expected.push_back(kernel::ism_kernel_indices(kernel_, readings[next]));
        accepted_at.push_back(res.cycles);
        res.accept_cycles.push_back(res.cycles);
        if (opt.isolated) {
          timing_setup = true;
          setup_start = res.cycles;
        }
        ++next;
        offering = false;
      }
      if (y_valid && out_cell == 0 && !seen_first && !accepted_at.empty()) {
        res.latencies.push_back(res.cycles - accepted_at.front());
        res.first_cells.push_back(res.cycles);
        seen_first = true;
      }
      if (y_valid && y_ready) {
        if (expected.empty()) {
          ++res.protocol_errors;
          error("a cell came out with no reading pending");
        } else {
          const int got = sign_extend(y_data, index_bits);
          const int want = expected.front()[out_cell];
          if (got != want) {
            ++res.mismatches;
            error("reading " + std::to_string(res.readings) + " (z = " +
                  std::to_string(readings[res.readings]) + ") cell " + std::to_string(out_cell) +
                  ": got " + std::to_string(got) + ", golden " + std::to_string(want));
          }
          const bool last = out_cell + 1 == cells_per_reading;
          if (bool(y_last) != last) {
            ++res.protocol_errors;
            error("y_last " + std::to_string(y_last) + " on cell " + std::to_string(out_cell));
          }
          ++res.cells;
          if (last) {
            expected.pop_front();
            accepted_at.pop_front();
            out_cell = 0;
            seen_first = false;
            ++res.readings;
          } else {
            ++out_cell;
          }
        }
      }
      idle = (z_fire || (y_valid && y_ready)) ? 0 : idle + 1;
      if (idle > opt.max_idle_cycles) {
        ++res.protocol_errors;
        error("nothing moved for " + std::to_string(idle) + " cycles");
        break;
      }
      if (opt.stop_at_first_error && !res.ok()) break;
      tick();
      ++res.cycles;
      if (assertion_failed()) {  // counted, then re-armed: the run goes on
        ++res.assertion_failures;
        error("an RTL assertion failed (its %Error line is printed above)");
        clear_assertion_failure();
      }
    }
    // Nothing more may come out.
    model_->y_ready_i = 1;
    model_->z_valid_i = 0;
    for (int i = 0; i < 64 && !res.stopped && res.assertion_failures == 0; ++i) {
      model_->eval();
      if (model_->y_valid_o) {
        ++res.protocol_errors;
        error("a cell came out after the last reading");
        break;
      }
      tick();
    }
    res.port_hash = hash;
    res.host_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
  }

  // Synchronous reset for `cycles` cycles, then one cycle out of reset, inputs idle except that
  // a reading is offered during the reset when `offer`. Returns the cycles, from the first reset
  // edge to the first cycle out of reset, in which z_ready was high (the RTL promises none).
  int reset(int cycles, bool offer = false) {
    int ready = 0;
    model_->rst_ni = 0;
    model_->z_valid_i = offer;
    model_->z_data_i = 0;
    model_->y_ready_i = 0;
    model_->eval();
    for (int i = 0; i < cycles; ++i) {
      tick();
      ready += model_->z_ready_o;
    }
    model_->rst_ni = 1;
    model_->z_valid_i = 0;  // withdrawn in reset: out of reset an offer would have to stay
    model_->eval();
    ready += model_->z_ready_o;
    tick();
    return ready;
  }
  // The model's ports, for directed tests; tick() clocks it once.
  Model& model() {
    return *model_;
  }
  void tick() {
    model_->clk_i = 1;
    model_->eval();
#if VM_TRACE
    if (trace_) trace_->dump(time_ + 5);
#endif
    model_->clk_i = 0;
    model_->eval();
    time_ += 10;
#if VM_TRACE
    if (trace_) trace_->dump(time_);
#endif
  }
  // Whether an RTL assertion has failed since the model was built (or the last clear).
  bool assertion_failed() const {
    return context_->gotError();
  }
  void clear_assertion_failure() {
    context_->gotError(false);
    context_->gotFinish(false);
  }

 private:
  static int index_bits_of(int max_index) {
    int b = 1;
    while ((1 << (b - 1)) - 1 < max_index) ++b;
    return b;
  }
  static int sign_extend(std::uint32_t v, int bits) {
    const std::uint32_t m = 1u << (bits - 1);
    return static_cast<int>((v & ((1u << bits) - 1)) ^ m) - static_cast<int>(m);
  }
  const kernel::IsmKernelTables& kernel_;
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Model> model_;
#if VM_TRACE
  std::unique_ptr<VerilatedFstC> trace_;
#endif
  std::uint64_t time_ = 0;
};

}  // namespace intgrid::hw
