// SystemC co-simulation of kernel 2, the sectoral ISM: the Verilated RTL (verilator --sc) and
// the SystemC model (systemc/sectoral_ism_module.hpp, the micro-architecture cycle by cycle)
// side by side on one clock and one stimulus (the same input signals, the same random gaps,
// the same random back-pressure, one reset in mid-stream at a random cycle).
//
// Checked in the middle of every cycle out of reset (both models settled):
//   - every port: z_ready and y_valid, and while valid y_data and y_last;
//   - the index RAM write port: we, and while we the address {bank, ring, sector} and the
//     data (the RTL's signals are public through testbench/sectoral_ism_cosim.vlt);
//   - the RTL's index writes against golden: each written index equals golden's index of that
//     (ring, sector) for the reading in set-up;
//   - once, the widths the RTL top derives against golden's (also public through the .vlt).
// In reset the model's z_ready must be low from the first edge that sees rst_n low (the reset
// is synchronous: in the cycle rst_n falls, z_ready still shows the state before it); the RTL's
// is compared only out of reset.
// The first differing cycle and signal are reported. Each model's output stream is also
// checked against golden's ism_kernel_indices by its own scoreboard (order, last flags, no
// drop or duplicate, outputs stable while valid && !ready).
//
// Stimulus: the edge readings and 150 random ones, every 4th offered only to an idle kernel so
// that set-up lengths show at the ports. With --bank-starts: 150 readings past the reach (the
// shortest set-ups), each offered only once at most 2 cells of the stream are unsent, no gaps
// and y_ready at random half the time, so that every bank starts under back-pressure (what
// SectoralIsmRtl.Cone16BackPressureWastesNoReadyCycle does to the RTL alone): a bubble at a bank
// start in either model shows as a y_valid mismatch.
//
//   sectoral_ism_cosim <cone16|cone12|cone16_bug_phi> [seed] [--fault rtl_phi|sc_schedule]
//                      [--bank-starts]
// (without a seed: INTGRID_ISM_SEED, else 42).
// cone16_bug_phi is the RTL built with log_add_phi. With --fault, the run must fail,
// and at the right cycle: rtl_phi, on the index RAM write data at the RTL's first index write
// that differs from golden; sc_schedule (the build sectoral_ism_cosim_sc_bug, whose SystemC
// set-up schedule has one suffix cycle more: intgrid_systemc_fault in sectoral_ism.cmake), on the
// write enable at the RTL's first index write.
// Prints one JSON line; exit status 0 when the run is as expected, 1 otherwise.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <systemc>

#include "Vsectoral_ism_sc_cone12.h"
#include "Vsectoral_ism_sc_cone12___024root.h"
#include "Vsectoral_ism_sc_cone12_sectoral_ism.h"
#include "Vsectoral_ism_sc_cone16.h"
#include "Vsectoral_ism_sc_cone16___024root.h"
#include "Vsectoral_ism_sc_cone16_bug.h"
#include "Vsectoral_ism_sc_cone16_bug___024root.h"
#include "Vsectoral_ism_sc_cone16_bug_sectoral_ism.h"
#include "Vsectoral_ism_sc_cone16_sectoral_ism.h"
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
  std::size_t cell = 0, readings = 0, lost = 0, cells = 0, errors = 0;
  bool stalled = false;
  Outputs previous;
  std::string first_error;

  void fail(const std::string& what, std::uint64_t cycle) {
    if (errors++ == 0) first_error = "cycle " + std::to_string(cycle) + ": " + what;
  }
  // A reset: the readings accepted and not sent are lost.
  void reset() {
    lost += expected.size();
    expected.clear();
    cell = 0;
    stalled = false;
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

enum class Fault { None, RtlPhi, ScSchedule };

struct Cosim {
  virtual ~Cosim() = default;
  virtual bool done() const = 0;
  virtual bool ok() const = 0;
  virtual void print(double seconds) const = 0;
};

template <class VModel, class Config>
struct CosimPair : sc_core::sc_module, Cosim {
  using Write = typename sc::SectoralIsmModule<Config>::IndexRamWrite;
  static constexpr int kSectorBits = sc::SectoralIsmSetup<Config>::kSectorBits;
  static constexpr int kBankBits = sc::SectoralIsmModule<Config>::kBankBits;

  sc_core::sc_in<bool> clk{"clk"};
  sc_signal<bool> rst_n{"rst_n"}, z_valid{"z_valid"}, z_last{"z_last"}, y_ready{"y_ready"};
  sc_signal<std::uint32_t> z_data{"z_data"};
  sc_signal<bool> rtl_z_ready{"rtl_z_ready"}, rtl_y_valid{"rtl_y_valid"}, rtl_y_last{"rtl_y_last"};
  sc_signal<std::uint32_t> rtl_y_data{"rtl_y_data"};
  sc_signal<bool> sc_z_ready{"sc_z_ready"}, sc_y_valid{"sc_y_valid"}, sc_y_last{"sc_y_last"};
  sc_signal<std::uint32_t> sc_y_data{"sc_y_data"};

  VModel rtl{"rtl"};
  sc::SectoralIsmModule<Config> model{"model"};

  const char* name_;
  Fault fault_;
  bool bank_starts_;
  IsmKernelTables kernel;
  std::vector<std::uint32_t> readings;
  std::mt19937_64 rng;
  Scoreboard rtl_board, model_board;
  std::uint64_t cycle = 0;  // cycles out of reset, counted in the middle of each cycle
  std::uint64_t cycle_mismatches = 0, first_mismatch_cycle = 0;
  std::string first_mismatch, first_mismatch_signal;
  // The reading the engine sets up (the last one accepted) and golden's indices of it.
  std::vector<std::int16_t> in_setup;
  std::uint64_t rtl_writes = 0, rtl_write_errors = 0, first_rtl_write = 0,
                first_rtl_write_error = 0;
  std::string first_write_error;
  bool resets_done = false, finished = false;
  std::uint64_t reset_cycles = 0;  // consecutive cycles with rst_n low, counted by compare()

  SC_HAS_PROCESS(CosimPair);
  CosimPair(const sc_core::sc_module_name& name, const char* config_name, std::uint64_t seed,
            Fault fault, bool bank_starts)
      : sc_core::sc_module(name),
        name_(config_name),
        fault_(fault),
        bank_starts_(bank_starts),
        kernel(make_ism_hw_kernel(ism_hw_config(Config::name))),
        rng(seed) {
    if (bank_starts_) {
      for (std::uint32_t i = 0; i < 150; ++i) readings.push_back(kernel.reach + i);
    } else {
      readings = ism_edge_readings(kernel, kIsmReadingBits);
      const auto r = ism_random_readings(kernel, kIsmReadingBits, 150, seed);
      readings.insert(readings.end(), r.begin(), r.end());
    }
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
    SC_CTHREAD(compare, clk.neg());
  }

  bool done() const override { return finished; }

  // The RTL's index RAM write port: {wb_q, idx_waddr} as i_index_ram sees it.
  Write rtl_write() {
    const auto* r = rtl.rootp;
    const auto* top = r->sectoral_ism;
    return {top->idx_we != 0,
            (std::uint32_t(top->wb_q) << kBankBits) | std::uint32_t(top->idx_waddr),
            std::uint32_t(top->idx_wdata)};
  }

  // The widths the RTL top derives (rtl/sectoral_ism_pkg.sv) against golden's derivation of the
  // same configuration, which the sub-modules' unit tests are Verilated with: "" when all agree.
  static std::string width_mismatches() {
    using Top = std::remove_pointer_t<decltype(std::declval<VModel>().rootp->sectoral_ism)>;
    const std::pair<const char*, std::pair<long, long>> widths[] = {
        {"MAX_INDEX", {Top::MAX_INDEX, Config::max_index}},
        {"E_W", {Top::E_W, Config::e_bits}},
        {"SQ_W", {Top::SQ_W, Config::sq_bits}},
        {"MUL_B_W", {Top::MUL_B_W, Config::mul_b_bits}},
        {"MUL_DIGIT_W", {Top::MUL_DIGIT_W, Config::mul_digit_bits}},
        {"PHI_AW", {Top::PHI_AW, Config::phi_addr_bits}},
        {"BUCKET_W", {Top::BUCKET_W, Config::bucket_bits}}};
    std::string out;
    for (const auto& [name, values] : widths)
      if (values.first != values.second)
        out += std::string(out.empty() ? "" : ", ") + name + " rtl " +
               std::to_string(values.first) + ", golden " + std::to_string(values.second);
    return out;
  }

  void mismatch(const char* signal, std::uint32_t rtl_value, std::uint32_t model_value) {
    if (cycle_mismatches++ != 0) return;
    first_mismatch_cycle = cycle;
    first_mismatch_signal = signal;
    first_mismatch = "cycle " + std::to_string(cycle) + ": " + signal + " rtl " +
                     std::to_string(rtl_value) + ", model " + std::to_string(model_value);
  }

  // In the middle of each cycle: every port and the index RAM write port of both models.
  void compare() {
    while (true) {
      wait();
      if (!rst_n.read()) {  // the model takes no reading in reset
        if (reset_cycles++ > 0 && sc_z_ready.read())
          model_board.fail("z_ready high in reset", cycle);
        continue;
      }
      reset_cycles = 0;
      const Write rw = rtl_write(), mw = model.index_ram_write();
      if (rtl_z_ready.read() != sc_z_ready.read())
        mismatch("z_ready", rtl_z_ready.read(), sc_z_ready.read());
      else if (rtl_y_valid.read() != sc_y_valid.read())
        mismatch("y_valid", rtl_y_valid.read(), sc_y_valid.read());
      else if (rtl_y_valid.read() && rtl_y_data.read() != sc_y_data.read())
        mismatch("y_data", rtl_y_data.read(), sc_y_data.read());
      else if (rtl_y_valid.read() && rtl_y_last.read() != sc_y_last.read())
        mismatch("y_last", rtl_y_last.read(), sc_y_last.read());
      else if (rw.we != mw.we)
        mismatch("index_ram_we", rw.we, mw.we);
      else if (rw.we && rw.addr != mw.addr)
        mismatch("index_ram_waddr", rw.addr, mw.addr);
      else if (rw.we && rw.data != mw.data)
        mismatch("index_ram_wdata", rw.data, mw.data);
      if (rw.we) check_rtl_write(rw);
      ++cycle;
    }
  }

  // An RTL index write against golden's index of its (ring, sector).
  void check_rtl_write(const Write& w) {
    if (rtl_writes++ == 0) first_rtl_write = cycle;
    if (in_setup.empty()) {  // a write before any reading
      if (rtl_write_errors++ == 0) {
        first_rtl_write_error = cycle;
        first_write_error = "cycle " + std::to_string(cycle) + ": a write with no reading";
      }
      return;
    }
    const std::uint32_t ring = (w.addr & ((1u << kBankBits) - 1)) >> kSectorBits;
    const std::uint32_t sector = w.addr & ((1u << kSectorBits) - 1);
    const std::size_t cell = ring * Config::bins + sector * Config::bins_per_sector;
    const std::uint32_t want =
        static_cast<std::uint32_t>(in_setup.at(cell)) & ((1u << Config::index_bits) - 1);
    if (w.data == want) return;
    if (rtl_write_errors++ == 0) {
      first_rtl_write_error = cycle;
      first_write_error = "cycle " + std::to_string(cycle) + ": ring index " +
                          std::to_string(ring) + " sector " + std::to_string(sector) + ": " +
                          std::to_string(w.data) + ", golden " + std::to_string(want);
    }
  }

  static Outputs sample(const sc_signal<bool>& zr, const sc_signal<bool>& yv,
                        const sc_signal<std::uint32_t>& yd, const sc_signal<bool>& yl) {
    return Outputs{zr.read(), yv.read(), yl.read(), yd.read()};
  }

  void hold_reset(int cycles) {
    rst_n.write(false);
    z_valid.write(false);
    y_ready.write(false);
    for (int i = 0; i < cycles; ++i) wait();
    rst_n.write(true);
    wait();  // the first cycle out of reset
  }

  // At each rising edge: the outputs of the cycle that ends, scored; the next cycle's inputs.
  void drive() {
    std::bernoulli_distribution gap(bank_starts_ ? 0.0 : 0.3), ready(bank_starts_ ? 0.5 : 0.6);
    hold_reset(4);
    std::size_t next = 0;
    bool offering = false, ready_now = false;
    std::uint64_t quiet = 0;
    // One reset in mid-stream, at a random cycle after half the readings are offered.
    std::uint64_t reset_countdown = std::uniform_int_distribution<std::uint64_t>(0, 3000)(rng);
    while (true) {
      wait();
      const std::uint64_t now = cycle - 1;  // the cycle that just ended
      const Outputs r = sample(rtl_z_ready, rtl_y_valid, rtl_y_data, rtl_y_last);
      const Outputs m = sample(sc_z_ready, sc_y_valid, sc_y_data, sc_y_last);
      const std::uint32_t offered = offering ? readings[next] : 0;
      rtl_board.cycle(r, offering && r.z_ready, offered, ready_now, now);
      model_board.cycle(m, offering && m.z_ready, offered, ready_now, now);
      const bool moved = (offering && r.z_ready) || (r.y_valid && ready_now);
      if (offering && r.z_ready) {
        in_setup = ism_kernel_indices(kernel, readings[next]);
        ++next;
        offering = false;
      }
      quiet = moved ? 0 : quiet + 1;
      const bool drained = rtl_board.expected.empty() && model_board.expected.empty();
      if ((next == readings.size() && drained) || quiet > 100000) break;
      if (!resets_done && 2 * next >= readings.size() && reset_countdown-- == 0) {
        resets_done = true;
        rtl_board.reset();
        model_board.reset();
        offering = false;
        hold_reset(3);
      }
      // Inputs of the next cycle.
      // Every 4th reading waits for an idle kernel (all output sent): the set-up's own length
      // then shows at the ports instead of hiding behind the other bank's output. With
      // --bank-starts each reading waits until at most 2 cells are unsent.
      std::size_t unsent = 0;
      for (const auto& e : rtl_board.expected) unsent += e.size();
      unsent -= rtl_board.cell;
      const bool wait_for_stream = bank_starts_ ? unsent > 2 : next % 4 == 3 && !drained;
      if (!offering && next < readings.size() && !gap(rng) && !wait_for_stream) offering = true;
      ready_now = ready(rng);
      z_valid.write(offering);
      z_last.write(offering);
      z_data.write(offering ? readings[next] : 0xbeef);
      y_ready.write(ready_now);
    }
    z_valid.write(false);
    y_ready.write(true);
    finished = true;
  }

  bool clean() const {
    return width_mismatches().empty() && cycle_mismatches == 0 && rtl_write_errors == 0 &&
           rtl_board.errors == 0 && model_board.errors == 0 &&
           rtl_board.readings + rtl_board.lost == readings.size() &&
           model_board.readings + model_board.lost == readings.size();
  }
  // The fault is caught, first by the check that must see it first, at the cycle it shows.
  bool caught() const {
    if (fault_ == Fault::RtlPhi)
      return rtl_write_errors > 0 && first_mismatch_signal == "index_ram_wdata" &&
             first_mismatch_cycle == first_rtl_write_error;
    return rtl_writes > 0 && first_mismatch_signal == "index_ram_we" &&
           first_mismatch_cycle == first_rtl_write;
  }
  bool ok() const override { return fault_ == Fault::None ? clean() : caught(); }

  void print(double seconds) const override {
    std::printf(
        "{\"kernel\": \"sectoral_ism\", \"test\": \"cosim\", \"config\": \"%s\", \"readings\": "
        "%zu, \"lost_to_reset\": %zu, \"cells\": %zu, \"cycles\": %llu, \"index_writes\": %llu, "
        "\"cycle_mismatches\": %llu, \"rtl_write_errors\": %llu, \"rtl_errors\": %zu, "
        "\"model_errors\": %zu, \"seconds\": %.2f, \"cycles_per_second\": %.0f, \"ok\": %s}\n",
        name_, rtl_board.readings, rtl_board.lost, rtl_board.cells,
        static_cast<unsigned long long>(cycle), static_cast<unsigned long long>(rtl_writes),
        static_cast<unsigned long long>(cycle_mismatches),
        static_cast<unsigned long long>(rtl_write_errors), rtl_board.errors, model_board.errors,
        seconds, double(cycle) / seconds, ok() ? "true" : "false");
    if (const std::string widths = width_mismatches(); !widths.empty())
      std::printf("  derived widths unlike golden's: %s\n", widths.c_str());
    if (!first_mismatch.empty())
      std::printf("  first rtl/model mismatch: %s\n", first_mismatch.c_str());
    if (!first_write_error.empty())
      std::printf("  first rtl index write unlike golden: %s\n", first_write_error.c_str());
    if (rtl_writes > 0)
      std::printf("  first rtl index write: cycle %llu\n",
                  static_cast<unsigned long long>(first_rtl_write));
    if (!rtl_board.first_error.empty()) std::printf("  rtl: %s\n", rtl_board.first_error.c_str());
    if (!model_board.first_error.empty())
      std::printf("  model: %s\n", model_board.first_error.c_str());
    if (fault_ != Fault::None)
      std::printf("  fault %s: %s\n", fault_ == Fault::RtlPhi ? "rtl_phi" : "sc_schedule",
                  caught() ? "caught at its first cycle" : "NOT caught as expected");
  }
};

int usage() {
  std::fprintf(stderr,
               "usage: sectoral_ism_cosim <cone16|cone12|cone16_bug_phi> [seed] "
               "[--fault rtl_phi|sc_schedule] [--bank-starts]\n");
  return 2;
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  if (argc < 2) return usage();
  const std::string config = argv[1];
  const char* seed_arg = nullptr;
  Fault fault = Fault::None;
  bool bank_starts = false;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--bank-starts") {
      bank_starts = true;
    } else if (arg == "--fault" && i + 1 < argc) {
      const std::string f = argv[++i];
      if (f == "rtl_phi")
        fault = Fault::RtlPhi;
      else if (f == "sc_schedule")
        fault = Fault::ScSchedule;
      else
        return usage();
    } else {
      seed_arg = argv[i];
    }
  }
  std::uint64_t seed = 0;
  if (seed_arg) {
    seed = std::strtoull(seed_arg, nullptr, 0);
    std::printf("[sectoral_ism_cosim] seed %llu (command line)\n",
                static_cast<unsigned long long>(seed));
  } else {
    seed = ism_bench_seed(42, "sectoral_ism_cosim");
  }
  sc_core::sc_clock clk("clk", 10, sc_core::SC_NS);
  std::unique_ptr<Cosim> run;
  if (config == "cone16") {
    auto p = std::make_unique<CosimPair<Vsectoral_ism_sc_cone16, SectoralIsmCone16>>(
        "cone16", "cone16", seed, fault, bank_starts);
    p->clk(clk);
    run = std::move(p);
  } else if (config == "cone12") {
    auto p = std::make_unique<CosimPair<Vsectoral_ism_sc_cone12, SectoralIsmCone12>>(
        "cone12", "cone12", seed, fault, bank_starts);
    p->clk(clk);
    run = std::move(p);
  } else if (config == "cone16_bug_phi") {
    auto p = std::make_unique<CosimPair<Vsectoral_ism_sc_cone16_bug, SectoralIsmCone16>>(
        "cone16_bug_phi", "cone16_bug_phi", seed, fault, bank_starts);
    p->clk(clk);
    run = std::move(p);
  } else {
    return usage();
  }
  const auto t0 = std::chrono::steady_clock::now();
  while (!run->done()) sc_core::sc_start(10000, sc_core::SC_NS);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run->print(seconds);
  return run->ok() ? 0 : 1;
}
