// A Verilator C++ bench of the sectoral ISM RTL (top `sectoral_ism`, one Verilated model
// per configuration): drives readings with random input gaps against random output
// back-pressure and checks, cycle by cycle,
//   - every output beat against golden's ism_kernel_indices of the reading it belongs to,
//     in order, with y_last exactly on each reading's last cell (no drop, no duplicate);
//   - y_valid, y_data and y_last stable while y_valid && !y_ready;
//   - nothing comes out that was not asked for, and everything asked for comes out.
// It measures set-up cycles (reading accepted -> z_ready again, idle kernel), latency
// (reading accepted -> its first cell valid) and total cycles.
#pragma once

#include <verilated.h>
#if VM_TRACE
#include <verilated_vcd_c.h>
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
  bool stop_at_first_error = false;
  std::uint64_t max_idle_cycles = 100000;  // fail if nothing moves this long
};

struct IsmBenchResult {
  std::size_t readings = 0, cells = 0;
  std::size_t mismatches = 0, protocol_errors = 0;
  std::uint64_t cycles = 0;
  double host_seconds = 0.0;
  std::vector<std::uint64_t> setup_cycles;  // per reading (isolated runs)
  std::vector<std::uint64_t> latencies;     // per reading: accepted -> first cell valid
  std::vector<std::string> errors;          // the first few, readable
  bool ok() const { return mismatches == 0 && protocol_errors == 0 && errors.empty(); }
  std::string summary() const {
    std::ostringstream s;
    s << readings << " readings, " << cells << " cells, " << cycles << " cycles, " << mismatches
      << " mismatching cells, " << protocol_errors << " protocol errors";
    for (const std::string& e : errors) s << "\n  " << e;
    return s.str();
  }
};

template <class Model>
class IsmRtlBench {
 public:
  // trace_path: a VCD file to dump (needs a model verilated with TRACE), or empty.
  IsmRtlBench(const kernel::IsmKernelTables& kernel, const std::string& trace_path = {})
      : kernel_(kernel), context_(std::make_unique<VerilatedContext>()) {
    context_->randReset(0);
    model_ = std::make_unique<Model>(context_.get());
#if VM_TRACE
    if (!trace_path.empty()) {
      context_->traceEverOn(true);
      trace_ = std::make_unique<VerilatedVcdC>();
      model_->trace(trace_.get(), 99);
      trace_->open(trace_path.c_str());
    }
#else
    (void)trace_path;
#endif
    reset();
  }
  ~IsmRtlBench() {
#if VM_TRACE
    if (trace_) trace_->close();
#endif
    model_->final();
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
    std::uint64_t idle = 0, setup_start = 0;
    bool timing_setup = false;
    const auto error = [&](const std::string& e) {
      if (res.errors.size() < 8)
        res.errors.push_back("cycle " + std::to_string(res.cycles) + ": " + e);
    };
    const auto t0 = std::chrono::steady_clock::now();
    while (next < readings.size() || !expected.empty()) {
      // Inputs for this cycle.
      if (!offering && next < readings.size()) {
        const bool drained = expected.empty() && !timing_setup;
        if ((!opt.isolated || drained) && !gap(rng)) offering = true;
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
        if (opt.isolated) {
          timing_setup = true;
          setup_start = res.cycles;
        }
        ++next;
        offering = false;
      }
      if (y_valid && out_cell == 0 && !seen_first && !accepted_at.empty()) {
        res.latencies.push_back(res.cycles - accepted_at.front());
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
    }
    // Nothing more may come out.
    model_->y_ready_i = 1;
    model_->z_valid_i = 0;
    for (int i = 0; i < 64; ++i) {
      model_->eval();
      if (model_->y_valid_o) {
        ++res.protocol_errors;
        error("a cell came out after the last reading");
        break;
      }
      tick();
    }
    res.host_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
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
  void reset() {
    model_->clk_i = 0;
    model_->rst_ni = 0;
    model_->z_valid_i = 0;
    model_->y_ready_i = 0;
    model_->eval();
    for (int i = 0; i < 4; ++i) tick();
    model_->rst_ni = 1;
    model_->eval();
    tick();
  }

  const kernel::IsmKernelTables& kernel_;
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Model> model_;
#if VM_TRACE
  std::unique_ptr<VerilatedVcdC> trace_;
#endif
  std::uint64_t time_ = 0;
};

}  // namespace intgrid::hw
