// SystemC co-simulation of kernel 1: the Verilated RTL (verilator --sc) and the SystemC model
// (systemc/index_fusion_module.hpp) side by side on one clock, driven by the same stimulus (same
// valid gaps, same data, same back-pressure), each checked against golden fuse_indices by its own
// scoreboard (testbench/index_fusion_tb.hpp), and compared with each other on every cycle: a_ready,
// b_ready, y_valid, y_data and y_last must be equal before every rising edge.
//
// Two configurations run at once, each a pair of models with its own stimulus:
//   B = 8,  LANES = 8 (the default, 64-bit bus): every lane sees all 65,536 input pairs;
//   B = 12, LANES = 6 (72-bit bus, lanes straddle 64-bit words): 2^16 random beats.
// The control signals (clock, reset, valids, lasts, y_ready) are shared by both models. The data
// buses cannot be: the SystemC model's are sc_biguint<LANES*B>, while the Verilated model's are
// Verilator's default SystemC types (uint64_t up to 64 bits, sc_bv<W> beyond). Verilator 5.006's
// --pins-sc-biguint would make them sc_biguint too, but its sc_biguint outputs always read as zero
// (VL_ASSIGN_SBW fills the digits through get_raw() and leaves the sign field at SC_ZERO; fixed
// upstream by verilator PR #4870, 2024). So each data input has one signal per model, both written
// with the same value in the same delta cycle.
//
// Prints one JSON line per configuration (beats, cycles, latency, and the simulation speed of the
// whole run in clock cycles per second of host time, all four models together); exit status 0
// when everything agrees, 1 otherwise. INTGRID_TB_SEED reproduces a run.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include <systemc>

#include "Vindex_fusion_sc_b12_l6.h"
#include "Vindex_fusion_sc_b8_l8.h"
#include "systemc/index_fusion_module.hpp"
#include "testbench/index_fusion_tb.hpp"
#include "testbench/stream_systemc.hpp"

namespace {

using namespace intgrid::tb;
using sc_core::sc_signal;

// The outputs of one model, as signals.
template <class T, int WIDTH>
struct OutputSignals {
  sc_signal<bool> a_ready, b_ready, y_valid, y_last;
  sc_signal<T> y_data;
  FusionOutputs read() const {
    FusionOutputs o;
    o.a_ready = a_ready.read();
    o.b_ready = b_ready.read();
    o.y_valid = y_valid.read();
    o.y_last = y_last.read();
    o.y_data = from_value(y_data.read(), WIDTH);
    return o;
  }
};

template <class VModel, int B, int LANES>
struct CosimPair : sc_core::sc_module {
  sc_core::sc_in<bool> clk{"clk"};

  static constexpr int kWidth = B * LANES;
  // The value types of the two models' data ports.
  using RtlData =
      typename std::remove_reference_t<decltype(std::declval<VModel&>().a_data_i)>::data_type;
  using ModelData = sc_dt::sc_biguint<kWidth>;

  // Shared control inputs; one data signal per model, written together.
  sc_signal<bool> rst_n{"rst_n"}, a_valid{"a_valid"}, a_last{"a_last"}, b_valid{"b_valid"},
      b_last{"b_last"}, y_ready{"y_ready"};
  sc_signal<RtlData> a_data_rtl{"a_data_rtl"}, b_data_rtl{"b_data_rtl"};
  sc_signal<ModelData> a_data_model{"a_data_model"}, b_data_model{"b_data_model"};
  OutputSignals<RtlData, kWidth> rtl_out;
  OutputSignals<ModelData, kWidth> model_out;

  VModel rtl{"rtl"};
  intgrid::sc::IndexFusionModule<B, LANES> model{"model"};

  FusionDriver<B, LANES> driver;
  FusionScoreboard<B, LANES> rtl_board, model_board;
  std::uint64_t cycle_mismatches = 0;
  std::vector<std::string> messages;
  bool done = false;
  std::uint64_t cycles = 0;

  SC_HAS_PROCESS(CosimPair);
  CosimPair(const sc_core::sc_module_name& name, const FusionStimulus<B, LANES>& stimulus,
            std::uint64_t seed)
      : sc_core::sc_module(name),
        driver(stimulus, TrafficShaper(splitmix64(seed + 1)), splitmix64(seed + 2)),
        rtl_board(std::string(name) + "/rtl"),
        model_board(std::string(name) + "/systemc") {
    bind(rtl);
    rtl.a_data_i(a_data_rtl);
    rtl.b_data_i(b_data_rtl);
    rtl.a_ready_o(rtl_out.a_ready);
    rtl.b_ready_o(rtl_out.b_ready);
    rtl.y_valid_o(rtl_out.y_valid);
    rtl.y_last_o(rtl_out.y_last);
    rtl.y_data_o(rtl_out.y_data);
    bind(model);
    model.a_data_i(a_data_model);
    model.b_data_i(b_data_model);
    model.a_ready_o(model_out.a_ready);
    model.b_ready_o(model_out.b_ready);
    model.y_valid_o(model_out.y_valid);
    model.y_last_o(model_out.y_last);
    model.y_data_o(model_out.y_data);
    SC_CTHREAD(bench, clk.pos());
  }

  template <class M>
  void bind(M& m) {
    m.clk_i(clk);
    m.rst_ni(rst_n);
    m.a_valid_i(a_valid);
    m.a_last_i(a_last);
    m.b_valid_i(b_valid);
    m.b_last_i(b_last);
    m.y_ready_i(y_ready);
  }

  void apply(const FusionDrive<B, LANES>& d) {
    a_valid.write(d.a_valid);
    b_valid.write(d.b_valid);
    y_ready.write(d.y_ready);
    a_last.write(d.a_last);
    b_last.write(d.b_last);
    a_data_rtl.write(to_value<RtlData>(d.a_data, kWidth));
    b_data_rtl.write(to_value<RtlData>(d.b_data, kWidth));
    a_data_model.write(to_value<ModelData>(d.a_data, kWidth));
    b_data_model.write(to_value<ModelData>(d.b_data, kWidth));
  }

  void bench() {
    // Synchronous reset for three cycles, inputs idle.
    rst_n.write(false);
    a_valid.write(false);
    b_valid.write(false);
    y_ready.write(false);
    wait(3);
    rst_n.write(true);
    apply(driver.drive());
    std::uint64_t tail = 0, idle = 0;
    while (true) {
      wait();  // a rising edge: signals still hold the values settled before it
      const FusionDrive<B, LANES> d = driver.drive();
      const FusionOutputs r = rtl_out.read(), m = model_out.read();
      if (!(r == m)) {
        ++cycle_mismatches;
        if (messages.size() < 12) {
          char buf[200];
          std::snprintf(buf, sizeof buf,
                        "cycle %llu: rtl a_ready %d b_ready %d y_valid %d y_last %d, systemc "
                        "a_ready %d b_ready %d y_valid %d y_last %d, y_data %s",
                        static_cast<unsigned long long>(cycles), r.a_ready, r.b_ready, r.y_valid,
                        r.y_last, m.a_ready, m.b_ready, m.y_valid, m.y_last,
                        r.y_data == m.y_data ? "equal" : "differ");
          messages.push_back(std::string(name()) + ": " + buf);
        }
      }
      const bool moved = rtl_board.observe(d, r);
      model_board.observe(d, m);
      driver.advance(moved);
      apply(driver.drive());
      ++cycles;
      idle = (moved || (r.y_valid && d.y_ready)) ? 0 : idle + 1;
      if (idle > 20000) {
        rtl_board.stuck("no handshake for 20000 cycles");
        break;
      }
      if (rtl_board.protocol_errors() + model_board.protocol_errors() > 100 ||
          cycle_mismatches > 100)
        break;
      if (driver.finished() && rtl_board.in_flight() == 0 && model_board.in_flight() == 0 &&
          ++tail > 32)
        break;
    }
    done = true;
  }

  // Prints the verdict and the JSON line; returns true when all is well.
  // host_seconds and clock_cycles are those of the whole run (both pairs, four models).
  bool verdict(double host_seconds, double clock_cycles) const {
    const FusionResult r = rtl_board.result(), m = model_board.result();
    std::printf("[%s] rtl: %s\n[%s] systemc: %s\n[%s] cycles compared %llu, differing %llu\n",
                name(), r.summary().c_str(), name(), m.summary().c_str(), name(),
                static_cast<unsigned long long>(cycles),
                static_cast<unsigned long long>(cycle_mismatches));
    for (const std::string& s : messages) std::printf("  %s\n", s.c_str());
    const bool ok = done && r.ok() && m.ok() && cycle_mismatches == 0 &&
                    r.beats_out == driver.beats() && m.beats_out == driver.beats();
    std::printf(
        "{\"kernel\":\"index_fusion\",\"model\":\"cosim-systemc\",\"B\":%d,\"LANES\":%d,"
        "\"ok\":%s,\"beats\":%llu,\"cells\":%llu,\"cycles\":%llu,\"cycle_mismatches\":%llu,"
        "\"latency_cycles\":%s,\"run_host_seconds\":%.3f,\"run_clock_cycles_per_s\":%.4g}\n",
        B, LANES, ok ? "true" : "false", static_cast<unsigned long long>(r.beats_out),
        static_cast<unsigned long long>(r.cells_checked), static_cast<unsigned long long>(cycles),
        static_cast<unsigned long long>(cycle_mismatches), r.latency.json().c_str(), host_seconds,
        clock_cycles / host_seconds);
    return ok;
  }
};

}  // namespace

int sc_main(int, char*[]) {
  sc_core::sc_report_handler::set_actions("/IEEE_Std_1666/deprecated", sc_core::SC_DO_NOTHING);
  sc_core::sc_clock clk("clk", 10, sc_core::SC_NS);

  const std::uint64_t seed8 = test_seed("index_fusion_cosim_b8_l8");
  const std::uint64_t seed12 = test_seed("index_fusion_cosim_b12_l6");
  CosimPair<Vindex_fusion_sc_b8_l8, 8, 8> pair8(
      "b8_l8", FusionStimulus<8, 8>(Coverage::kExhaustive, 0, seed8), seed8);
  CosimPair<Vindex_fusion_sc_b12_l6, 12, 6> pair12(
      "b12_l6", FusionStimulus<12, 6>(Coverage::kRandom, std::uint64_t{1} << 16, seed12), seed12);
  pair8.clk(clk);
  pair12.clk(clk);

  const auto start = std::chrono::steady_clock::now();
  const sc_core::sc_time limit(100, sc_core::SC_MS);  // far beyond the ~300k cycles needed
  while (!(pair8.done && pair12.done) && sc_core::sc_time_stamp() < limit)
    sc_core::sc_start(100, sc_core::SC_US);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double clock_cycles = sc_core::sc_time_stamp() / clk.period();
  const bool ok8 = pair8.verdict(seconds, clock_cycles);
  const bool ok12 = pair12.verdict(seconds, clock_cycles);
  return ok8 && ok12 ? 0 : 1;
}
