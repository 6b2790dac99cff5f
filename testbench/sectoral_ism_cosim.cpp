// SystemC co-simulation of kernel 2, the sectoral ISM: the Verilated RTL (verilator --sc) and
// the SystemC model (systemc/sectoral_ism_module.hpp, which runs hls::sectoral_ism_kernel)
// side by side on one clock and one stimulus (the same input signals, the same random gaps,
// the same random back-pressure). On every cycle both must show the same z_ready, y_valid,
// and, while valid, the same y_data and y_last; each is also checked against golden's
// ism_kernel_indices by its own scoreboard (order, last flags, no drop or duplicate, outputs
// stable while valid && !ready).
//
// Both configurations run at once, each a pair of models with its own stimulus: the edge
// readings and 150 random ones, every 4th offered only to an idle kernel so that set-up
// lengths show at the ports. Prints one JSON line per configuration; exit status 0 when
// everything agrees, 1 otherwise. INTGRID_ISM_SEED reproduces a run.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include <systemc>

#include "Vsectoral_ism_sc_cone12.h"
#include "Vsectoral_ism_sc_cone16.h"
#include "intgrid/kernel/hardware_configs.hpp"
#include "intgrid/kernel/ism_kernel.hpp"
#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"
#include "systemc/sectoral_ism_module.hpp"
#include "testbench/sectoral_ism_rtl_bench.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;

namespace {

using namespace intgrid;
using namespace intgrid::hw;
using sc_core::sc_signal;

struct Outputs {
  bool z_ready = false, y_valid = false, y_last = false;
  std::uint32_t y_data = 0;
};

// Golden's view of one output stream.
struct Scoreboard {
  const IsmKernelTables* k = nullptr;
  int index_bits = 0;
  std::deque<std::vector<std::int16_t>> expected;
  std::size_t cell = 0, readings = 0, cells = 0, errors = 0;
  bool stalled = false;
  Outputs previous;
  std::string first_error;

  void fail(const std::string& what, std::uint64_t cycle) {
    if (errors++ == 0) first_error = "cycle " + std::to_string(cycle) + ": " + what;
  }
  // One cycle: the outputs, whether the reading offered was taken, and y_ready.
  void cycle(const Outputs& o, bool z_fire, std::uint32_t reading, bool y_ready,
             std::uint64_t now) {
    if (stalled && (!o.y_valid || o.y_data != previous.y_data || o.y_last != previous.y_last))
      fail("output changed while valid && !ready", now);
    stalled = o.y_valid && !y_ready;
    previous = o;
    if (z_fire) expected.push_back(ism_kernel_indices(*k, reading));
    if (!(o.y_valid && y_ready)) return;
    if (expected.empty()) return fail("a cell with no reading pending", now);
    const std::uint32_t m = 1u << (index_bits - 1);
    const int got = static_cast<int>((o.y_data & ((1u << index_bits) - 1)) ^ m) - int(m);
    if (got != expected.front()[cell])
      fail("cell " + std::to_string(cell) + ": " + std::to_string(got) + ", golden " +
               std::to_string(expected.front()[cell]),
           now);
    const bool last = cell + 1 == expected.front().size();
    if (o.y_last != last) fail("y_last wrong on cell " + std::to_string(cell), now);
    ++cells;
    if (last) {
      expected.pop_front();
      cell = 0;
      ++readings;
    } else {
      ++cell;
    }
  }
};

template <class VModel, class Config>
struct CosimPair : sc_core::sc_module {
  sc_core::sc_in<bool> clk{"clk"};
  sc_signal<bool> rst_n{"rst_n"}, z_valid{"z_valid"}, z_last{"z_last"}, y_ready{"y_ready"};
  sc_signal<std::uint32_t> z_data{"z_data"};
  sc_signal<bool> rtl_z_ready{"rtl_z_ready"}, rtl_y_valid{"rtl_y_valid"}, rtl_y_last{"rtl_y_last"};
  sc_signal<std::uint32_t> rtl_y_data{"rtl_y_data"};
  sc_signal<bool> sc_z_ready{"sc_z_ready"}, sc_y_valid{"sc_y_valid"}, sc_y_last{"sc_y_last"};
  sc_signal<std::uint32_t> sc_y_data{"sc_y_data"};

  VModel rtl{"rtl"};
  sc::SectoralIsmModule<Config> model{"model"};

  IsmKernelTables kernel;
  std::vector<std::uint32_t> readings;
  std::mt19937_64 rng;
  Scoreboard rtl_board, model_board;
  std::uint64_t cycles = 0, cycle_mismatches = 0;
  std::string first_mismatch;
  bool done = false;

  SC_HAS_PROCESS(CosimPair);
  CosimPair(const sc_core::sc_module_name& name, std::uint64_t seed)
      : sc_core::sc_module(name),
        kernel(make_ism_hw_kernel(ism_hw_config(Config::name))),
        rng(seed) {
    readings = ism_edge_readings(kernel, kIsmReadingBits);
    const auto r = ism_random_readings(kernel, kIsmReadingBits, 150, seed);
    readings.insert(readings.end(), r.begin(), r.end());
    for (Scoreboard* b : {&rtl_board, &model_board}) {
      b->k = &kernel;
      b->index_bits = Config::index_bits;
    }
    rtl.clk_i(clk);
    rtl.rst_ni(rst_n);
    rtl.z_valid_i(z_valid);
    rtl.z_ready_o(rtl_z_ready);
    rtl.z_data_i(z_data);
    rtl.z_last_i(z_last);
    rtl.y_valid_o(rtl_y_valid);
    rtl.y_ready_i(y_ready);
    rtl.y_data_o(rtl_y_data);
    rtl.y_last_o(rtl_y_last);
    model.clk(clk);
    model.rst_n(rst_n);
    model.z_valid(z_valid);
    model.z_ready(sc_z_ready);
    model.z_data(z_data);
    model.z_last(z_last);
    model.y_valid(sc_y_valid);
    model.y_ready(y_ready);
    model.y_data(sc_y_data);
    model.y_last(sc_y_last);
    SC_CTHREAD(drive, clk.pos());
  }

  static Outputs sample(const sc_signal<bool>& zr, const sc_signal<bool>& yv,
                        const sc_signal<std::uint32_t>& yd, const sc_signal<bool>& yl) {
    return Outputs{zr.read(), yv.read(), yl.read(), yd.read()};
  }

  // At each rising edge: the outputs of the cycle that ends, checked; the next cycle's inputs.
  void drive() {
    std::bernoulli_distribution gap(0.3), ready(0.6);
    rst_n.write(false);
    z_valid.write(false);
    y_ready.write(false);
    for (int i = 0; i < 4; ++i) wait();
    rst_n.write(true);
    wait();  // the first cycle out of reset
    std::size_t next = 0;
    bool offering = false, ready_now = false;
    std::uint64_t quiet = 0;
    while (true) {
      wait();
      const Outputs r = sample(rtl_z_ready, rtl_y_valid, rtl_y_data, rtl_y_last);
      const Outputs m = sample(sc_z_ready, sc_y_valid, sc_y_data, sc_y_last);
      if (r.z_ready != m.z_ready || r.y_valid != m.y_valid ||
          (r.y_valid && (r.y_data != m.y_data || r.y_last != m.y_last))) {
        if (cycle_mismatches++ == 0)
          first_mismatch = "cycle " + std::to_string(cycles) + ": rtl z_ready " +
                           std::to_string(r.z_ready) + " y_valid " + std::to_string(r.y_valid) +
                           " y_data " + std::to_string(r.y_data) + ", model z_ready " +
                           std::to_string(m.z_ready) + " y_valid " + std::to_string(m.y_valid) +
                           " y_data " + std::to_string(m.y_data);
      }
      const std::uint32_t offered = offering ? readings[next] : 0;
      rtl_board.cycle(r, offering && r.z_ready, offered, ready_now, cycles);
      model_board.cycle(m, offering && m.z_ready, offered, ready_now, cycles);
      const bool moved = (offering && r.z_ready) || (r.y_valid && ready_now);
      if (offering && r.z_ready) {
        ++next;
        offering = false;
      }
      ++cycles;
      quiet = moved ? 0 : quiet + 1;
      const bool finished =
          next == readings.size() && rtl_board.expected.empty() && model_board.expected.empty();
      if (finished || quiet > 100000) break;
      // Inputs of the next cycle.
      // Every 4th reading waits for an idle kernel (all output sent): the set-up's own length
      // then shows at the ports instead of hiding behind the other bank's output.
      const bool drained = rtl_board.expected.empty() && model_board.expected.empty();
      if (!offering && next < readings.size() && !gap(rng) && (next % 4 != 3 || drained))
        offering = true;
      ready_now = ready(rng);
      z_valid.write(offering);
      z_last.write(offering);
      z_data.write(offering ? readings[next] : 0xbeef);
      y_ready.write(ready_now);
    }
    z_valid.write(false);
    y_ready.write(true);
    done = true;
  }

  bool ok() const {
    return cycle_mismatches == 0 && rtl_board.errors == 0 && model_board.errors == 0 &&
           rtl_board.readings == readings.size() && model_board.readings == readings.size();
  }
  void print(double seconds, std::uint64_t all_cycles) const {
    std::printf(
        "{\"kernel\": \"sectoral_ism\", \"test\": \"cosim\", \"config\": \"%s\", \"readings\": "
        "%zu, \"cells\": %zu, \"cycles\": %llu, \"cycle_mismatches\": %llu, \"rtl_errors\": %zu, "
        "\"model_errors\": %zu, \"systemc_cycles_per_second\": %.0f, \"ok\": %s}\n",
        Config::name, rtl_board.readings, rtl_board.cells, static_cast<unsigned long long>(cycles),
        static_cast<unsigned long long>(cycle_mismatches), rtl_board.errors, model_board.errors,
        double(all_cycles) / seconds, ok() ? "true" : "false");
    if (!first_mismatch.empty())
      std::printf("  first rtl/model mismatch: %s\n", first_mismatch.c_str());
    if (!rtl_board.first_error.empty()) std::printf("  rtl: %s\n", rtl_board.first_error.c_str());
    if (!model_board.first_error.empty())
      std::printf("  model: %s\n", model_board.first_error.c_str());
  }
};

}  // namespace

int sc_main(int, char*[]) {
  const std::uint64_t seed = ism_bench_seed(42, "sectoral_ism_cosim");
  sc_core::sc_clock clk("clk", 10, sc_core::SC_NS);
  CosimPair<Vsectoral_ism_sc_cone16, SectoralIsmCone16> cone16("cone16", seed);
  CosimPair<Vsectoral_ism_sc_cone12, SectoralIsmCone12> cone12("cone12", seed + 1);
  cone16.clk(clk);
  cone12.clk(clk);
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t steps = 0;
  while (!(cone16.done && cone12.done)) {
    sc_core::sc_start(10000, sc_core::SC_NS);
    steps += 1000;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  cone16.print(seconds, steps);
  cone12.print(seconds, steps);
  return cone16.ok() && cone12.ok() ? 0 : 1;
}
