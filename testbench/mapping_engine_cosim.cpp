// Co-simulation of the mapping engine on the bundled real log: the Verilated RTL
// (rtl/mapping_engine.sv, verilator --sc) and the SystemC model (systemc/mapping_engine_module.hpp)
// on one clock, driven by one stimulus: every scan at its reference pose sent as a pose beat and
// its readings, with random gaps in the command stream, then the whole tile read out through the
// read port under random back-pressure and compared, cell for cell, with golden's integer
// insertion of the same scans (testbench/mapping_engine_log.hpp). The two are compared with each
// other before every rising edge: in_ready, rd_ready, rd_valid and idle, and rd_data while
// rd_valid. Also checks that the model walked as many cells as the HLS engine does for the same
// readings. Data inputs have one signal per model, written together (the Verilated ports are
// Verilator's integer types, the model's sc_int/sc_uint).
//
// The memories are loaded through the load port while the tile clears after reset.
//
// Prints one JSON line (scans, readings, cells walked, cycles from the first beat to idle, cycles
// a scan, cells walked a cycle, mismatches); exit status 0 when everything agrees, 1 otherwise.
// INTGRID_TB_SEED reproduces a run.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include <systemc>

#include "Vmapping_engine_sc.h"
#include "systemc/mapping_engine_module.hpp"
#include "testbench/mapping_engine_log.hpp"

namespace {

using namespace intgrid;
using sc_core::sc_signal;

constexpr int kTileBits = 8;
constexpr int kSide = 1 << kTileBits;
using Module = sc::MappingEngineModule<8, kTileBits, hw::kLogBins, 1 << 10>;
using HlsEngine = Module::Engine;

struct Bench : sc_core::sc_module {
  sc_core::sc_in<bool> clk{"clk"};

  sc_signal<bool> rst_n{"rst_n"}, in_valid{"in_valid"}, in_ready{"in_ready"}, in_pose{"in_pose"};
  sc_signal<sc_dt::sc_int<hls::mapping::kCoordBits>> in_cx{"in_cx"}, in_cy{"in_cy"};
  sc_signal<sc_dt::sc_int<hls::mapping::kCellBits + 1>> in_px{"in_px"}, in_py{"in_py"};
  sc_signal<sc_dt::sc_uint<16>> in_angle{"in_angle"};
  sc_signal<sc_dt::sc_uint<hls::mapping::kRangeBits>> in_range{"in_range"};
  sc_signal<bool> rd_valid{"rd_valid"}, rd_ready{"rd_ready"}, rd_valid_out{"rd_valid_out"},
      rd_ready_in{"rd_ready_in"}, idle{"idle"};
  sc_signal<sc_dt::sc_uint<2 * kTileBits>> rd_addr{"rd_addr"};
  sc_signal<sc_dt::sc_int<8>> rd_data{"rd_data"};
  sc_signal<bool> ld_valid{"ld_valid"};
  sc_signal<sc_dt::sc_uint<3>> ld_target{"ld_target"};
  sc_signal<sc_dt::sc_uint<16>> ld_addr{"ld_addr"};
  sc_signal<sc_dt::sc_uint<64>> ld_data{"ld_data"};
  // The RTL's data inputs and outputs.
  sc_signal<std::uint32_t> rtl_cx{"rtl_cx"}, rtl_cy{"rtl_cy"}, rtl_px{"rtl_px"}, rtl_py{"rtl_py"},
      rtl_angle{"rtl_angle"}, rtl_range{"rtl_range"}, rtl_rd_addr{"rtl_rd_addr"},
      rtl_ld_target{"rtl_ld_target"}, rtl_ld_addr{"rtl_ld_addr"}, rtl_rd_data{"rtl_rd_data"};
  sc_signal<std::uint64_t> rtl_ld_data{"rtl_ld_data"};
  sc_signal<bool> rtl_in_ready{"rtl_in_ready"}, rtl_rd_ready{"rtl_rd_ready"},
      rtl_rd_valid{"rtl_rd_valid"}, rtl_idle{"rtl_idle"};

  Module dut{"dut"};
  Vmapping_engine_sc rtl{"rtl"};
  std::uint64_t cycle_mismatches = 0;
  const hw::EngineLog& log;
  std::mt19937_64 rng;
  int* running;  // benches not finished yet

  // The load port's writes: the settings, the quarter-wave sine, the packed ISM table.
  struct Load {
    unsigned target, address;
    std::uint64_t data;
  };
  std::vector<Load> loads;
  std::size_t next_load = 0;
  // Progress, as members: nothing with a heap lives across a wait().
  std::size_t scan = 0, reading = 0;  // the next beat: a pose when reading == 0 and not sent
  bool pose_sent = false, sent_all = false;
  std::uint32_t next_read = 0, cells_read = 0;
  std::uint64_t mismatches = 0, first_beat_cycle = 0, idle_cycle = 0, cycle = 0;
  bool done = false;

  SC_HAS_PROCESS(Bench);
  Bench(const sc_core::sc_module_name& name, const hw::EngineLog& engine_log, std::uint64_t seed,
        int* benches_running)
      : sc_core::sc_module(name), log(engine_log), rng(seed), running(benches_running) {
    dut.clk_i(clk);
    dut.rst_ni(rst_n);
    dut.in_valid_i(in_valid);
    dut.in_ready_o(in_ready);
    dut.in_pose_i(in_pose);
    dut.in_cx_i(in_cx);
    dut.in_cy_i(in_cy);
    dut.in_px_i(in_px);
    dut.in_py_i(in_py);
    dut.in_angle_i(in_angle);
    dut.in_range_i(in_range);
    dut.rd_valid_i(rd_valid);
    dut.rd_ready_o(rd_ready);
    dut.rd_addr_i(rd_addr);
    dut.rd_valid_o(rd_valid_out);
    dut.rd_ready_i(rd_ready_in);
    dut.rd_data_o(rd_data);
    dut.idle_o(idle);
    dut.ld_valid_i(ld_valid);
    dut.ld_target_i(ld_target);
    dut.ld_addr_i(ld_addr);
    dut.ld_data_i(ld_data);
    rtl.clk_i(clk);
    rtl.rst_ni(rst_n);
    rtl.in_valid_i(in_valid);
    rtl.in_ready_o(rtl_in_ready);
    rtl.in_pose_i(in_pose);
    rtl.in_cx_i(rtl_cx);
    rtl.in_cy_i(rtl_cy);
    rtl.in_px_i(rtl_px);
    rtl.in_py_i(rtl_py);
    rtl.in_angle_i(rtl_angle);
    rtl.in_range_i(rtl_range);
    rtl.rd_valid_i(rd_valid);
    rtl.rd_ready_o(rtl_rd_ready);
    rtl.rd_addr_i(rtl_rd_addr);
    rtl.rd_valid_o(rtl_rd_valid);
    rtl.rd_ready_i(rd_ready_in);
    rtl.rd_data_o(rtl_rd_data);
    rtl.idle_o(rtl_idle);
    rtl.ld_valid_i(ld_valid);
    rtl.ld_target_i(rtl_ld_target);
    rtl.ld_addr_i(rtl_ld_addr);
    rtl.ld_data_i(rtl_ld_data);
    loads = {{0, 0, hw::kLogCellMm}, {0, 1, hw::kLogZStepMm}, {0, 2, hw::kLogMaxRangeMm}};
    for (std::size_t j = 0; j < log.packed_sine.coarse.size(); ++j)
      loads.push_back({1, static_cast<unsigned>(j), log.packed_sine.coarse[j]});
    for (std::size_t j = 0; j < log.packed_sine.steps.size(); ++j)
      loads.push_back({2, static_cast<unsigned>(j), log.packed_sine.steps[j]});
    for (std::size_t bin = 0; bin < log.packed.bins.size(); ++bin) {
      const hw::PackedIsmBin& b = log.packed.bins[bin];
      constexpr int kCount = Module::kCountBits;
      loads.push_back({3, static_cast<unsigned>(bin),
                       b.cells | (std::uint64_t{b.core} << kCount) |
                           (std::uint64_t{static_cast<std::uint8_t>(b.constant)} << (2 * kCount)) |
                           (std::uint64_t{b.tail} << (2 * kCount + 8))});
    }
    for (std::size_t i = 0; i < log.packed.tail.size(); ++i)
      loads.push_back({4, static_cast<unsigned>(i),
                       static_cast<std::uint64_t>(static_cast<std::uint8_t>(log.packed.tail[i]))});
    SC_CTHREAD(drive, clk.pos());
  }

  bool chance(int percent) { return static_cast<int>(rng() % 100) < percent; }

  // A field's two's-complement pattern on the RTL's port.
  static std::uint32_t pattern(std::int64_t v, int bits) {
    return static_cast<std::uint32_t>(v) & ((std::uint32_t{1} << bits) - 1u);
  }

  // The beat at (scan, reading) on the command stream's signals.
  void present_beat() {
    const hw::EngineScan& s = log.scans[scan];
    in_pose.write(!pose_sent);
    if (!pose_sent) {
      in_cx.write(s.pose.cx.value());
      in_cy.write(s.pose.cy.value());
      in_px.write(s.pose.px.value());
      in_py.write(s.pose.py.value());
      in_angle.write(static_cast<std::uint32_t>(s.pose.heading.value()));
      rtl_cx.write(pattern(s.pose.cx.value(), hls::mapping::kCoordBits));
      rtl_cy.write(pattern(s.pose.cy.value(), hls::mapping::kCoordBits));
      rtl_px.write(pattern(s.pose.px.value(), hls::mapping::kCellBits + 1));
      rtl_py.write(pattern(s.pose.py.value(), hls::mapping::kCellBits + 1));
      rtl_angle.write(static_cast<std::uint32_t>(s.pose.heading.value()));
    } else {
      in_angle.write(static_cast<std::uint32_t>(s.readings[reading].bearing.value()));
      in_range.write(static_cast<std::uint32_t>(s.readings[reading].range_mm.value()));
      rtl_angle.write(static_cast<std::uint32_t>(s.readings[reading].bearing.value()));
      rtl_range.write(static_cast<std::uint32_t>(s.readings[reading].range_mm.value()));
    }
  }

  // The two models' outputs before this edge.
  void compare() {
    const bool same =
        rtl_in_ready.read() == in_ready.read() && rtl_rd_ready.read() == rd_ready.read() &&
        rtl_rd_valid.read() == rd_valid_out.read() && rtl_idle.read() == idle.read() &&
        (!rd_valid_out.read() ||
         static_cast<std::int8_t>(rtl_rd_data.read()) == rd_data.read().to_int());
    if (!same && cycle_mismatches++ < 5) {
      std::fprintf(stderr,
                   "cycle %llu: in_ready %d/%d rd_ready %d/%d rd_valid %d/%d idle %d/%d rd_data "
                   "%d/%d (RTL/model)\n",
                   static_cast<unsigned long long>(cycle), rtl_in_ready.read(), in_ready.read(),
                   rtl_rd_ready.read(), rd_ready.read(), rtl_rd_valid.read(), rd_valid_out.read(),
                   rtl_idle.read(), idle.read(), static_cast<std::int8_t>(rtl_rd_data.read()),
                   rd_data.read().to_int());
    }
  }
  void next_beat() {
    if (!pose_sent) {
      pose_sent = true;
    } else if (++reading == log.scans[scan].readings.size()) {
      reading = 0;
      pose_sent = false;
      sent_all = ++scan == log.scans.size();
    }
  }

  void drive() {
    rst_n.write(false);
    in_valid.write(false);
    ld_valid.write(false);
    rd_valid.write(false);
    rd_ready_in.write(false);
    wait();
    wait();
    rst_n.write(true);
    while (!done) {
      wait();
      ++cycle;
      edge();
    }
    if (--*running == 0) sc_core::sc_stop();  // the last bench to finish ends the simulation
    while (true) wait();
  }

  // After each rising edge: what fired at it, then the next cycle's inputs.
  void edge() {
    compare();
    // The load port, one write a cycle from the first cycle out of reset.
    ld_valid.write(next_load < loads.size());
    if (next_load < loads.size()) {
      ld_target.write(loads[next_load].target);
      ld_addr.write(loads[next_load].address);
      ld_data.write(loads[next_load].data);
      rtl_ld_target.write(loads[next_load].target);
      rtl_ld_addr.write(loads[next_load].address);
      rtl_ld_data.write(loads[next_load].data);
      ++next_load;
    }
    // The command stream: a beat fired at this edge if it was valid and the slot was empty.
    if (in_valid.read() && in_ready.read()) {
      if (first_beat_cycle == 0) first_beat_cycle = cycle;
      next_beat();
    }
    if (!sent_all) {
      const bool hold = in_valid.read() && !in_ready.read();  // valid stays up until taken
      in_valid.write(hold || chance(75));
      if (!hold) present_beat();
    } else {
      in_valid.write(false);
    }
    // The read port, once everything was sent and the engine is idle.
    if (rd_valid_out.read() && rd_ready_in.read()) {
      const std::uint32_t address = cells_read++;
      const int x = static_cast<int>(address % kSide), y = static_cast<int>(address / kSide);
      if (rd_data.read().to_int() != log.golden.at(x, y)) {
        if (mismatches < 5)
          std::fprintf(stderr, "cell (%d, %d): model %d, golden %d\n", x, y,
                       rd_data.read().to_int(), log.golden.at(x, y));
        ++mismatches;
      }
      if (cells_read == kSide * kSide) done = true;
    }
    if (rd_valid.read() && rd_ready.read()) ++next_read;
    if (sent_all && idle.read() && !in_valid.read() && idle_cycle == 0) idle_cycle = cycle;
    const bool reading_out = idle_cycle != 0 && next_read < kSide * kSide;
    rd_valid.write(reading_out && chance(80));
    rd_addr.write(next_read);
    rtl_rd_addr.write(next_read & (kSide * kSide - 1u));
    rd_ready_in.write(chance(70));
  }
};

// The HLS engine's walk over a stimulus: the oracle of the model's walked cells.
std::uint64_t cells_walked_by_hls(const hw::EngineLog& log) {
  const auto engine = std::make_unique<HlsEngine>();
  hw::load_engine(*engine, log);
  std::uint64_t walked = 0;
  for (const hw::EngineScan& s : log.scans) {
    engine->begin_scan(s.pose);
    for (const hls::RangeReading& r : s.readings) walked += engine->insert(r);
  }
  return walked;
}

// One bench's line; true when it agrees with golden, the HLS walk and itself across the models.
bool report(const char* stimulus, const Bench& bench, std::uint64_t seed) {
  std::uint64_t readings = 0;
  for (const hw::EngineScan& s : bench.log.scans) readings += s.readings.size();
  const std::uint64_t walked = cells_walked_by_hls(bench.log);
  const std::uint64_t busy = bench.idle_cycle - bench.first_beat_cycle;
  const bool walk_agrees = bench.dut.cells_walked() == walked;
  std::printf(
      "{\"stimulus\": \"%s\", \"seed\": %llu, \"scans\": %zu, \"readings\": %llu, "
      "\"cells_walked\": %llu, \"cycles\": %llu, \"cycles_per_scan\": %.0f, "
      "\"cells_per_cycle\": %.3f, \"cells_read\": %u, \"mismatches\": %llu, "
      "\"rtl_model_cycle_mismatches\": %llu, \"walk_agrees_with_hls\": %s}\n",
      stimulus, static_cast<unsigned long long>(seed), bench.log.scans.size(),
      static_cast<unsigned long long>(readings),
      static_cast<unsigned long long>(bench.dut.cells_walked()),
      static_cast<unsigned long long>(busy),
      static_cast<double>(busy) / static_cast<double>(bench.log.scans.size()),
      static_cast<double>(bench.dut.cells_walked()) / static_cast<double>(busy), bench.cells_read,
      static_cast<unsigned long long>(bench.mismatches),
      static_cast<unsigned long long>(bench.cycle_mismatches), walk_agrees ? "true" : "false");
  return bench.done && bench.mismatches == 0 && bench.cycle_mismatches == 0 && walk_agrees &&
         busy >= walked;
}

}  // namespace

int sc_main(int, char*[]) {
  const char* seed_text = std::getenv("INTGRID_TB_SEED");
  const std::uint64_t seed = seed_text != nullptr ? std::strtoull(seed_text, nullptr, 10) : 1;
  const hw::EngineLog log = hw::engine_log(kSide);
  const hw::EngineLog ties = hw::tie_scans(kSide);
  sc_core::sc_clock clk("clk", 10, sc_core::SC_NS);
  int running = 2;
  const auto log_bench = std::make_unique<Bench>("log_bench", log, seed, &running);
  const auto tie_bench = std::make_unique<Bench>("tie_bench", ties, seed + 1, &running);
  log_bench->clk(clk);
  tie_bench->clk(clk);
  sc_core::sc_start();
  const bool log_ok = report("bundled log", *log_bench, seed);
  const bool ties_ok = report("ties", *tie_bench, seed);
  return log_ok && ties_ok ? 0 : 1;
}
