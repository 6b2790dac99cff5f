// Cycle-accurate SystemC model of the sectoral ISM kernel (rtl/sectoral_ism.sv): the same
// ports, the same ready/valid behaviour and the same cycle of every handshake as the RTL.
// The indices come from the synthesizable function hls::sectoral_ism_kernel; the timing
// from the RTL's schedule (systemc/sectoral_ism_timing.hpp) and a register-level copy of
// its bank flags, stream stage and spill register.
//
// One SC_CTHREAD on clk.pos(), reset while rst_n is low (synchronous, like the RTL). Every
// output is a register or a function of registers only, written after each edge, so a beat
// moves in the cycle where both sides' values are high at the next edge.
//
//   z_valid/z_ready/z_data/z_last  one reading per beat (z_data: reading_bits wide; z_last
//                                  ignored)
//   y_valid/y_ready/y_data/y_last  one cell index per beat (index_bits two's complement),
//                                  ring-major, y_last on each reading's last cell
#pragma once

#include <array>
#include <cstdint>

#include <systemc>

#include "hls/sectoral_ism.hpp"
#include "systemc/sectoral_ism_timing.hpp"

namespace intgrid::sc {

template <class Config>
struct SectoralIsmModule : sc_core::sc_module {
  static constexpr int kCells = Config::rings * Config::bins;

  sc_core::sc_in<bool> clk{"clk"};
  sc_core::sc_in<bool> rst_n{"rst_n"};
  sc_core::sc_in<bool> z_valid{"z_valid"};
  sc_core::sc_out<bool> z_ready{"z_ready"};
  sc_core::sc_in<std::uint32_t> z_data{"z_data"};
  sc_core::sc_in<bool> z_last{"z_last"};
  sc_core::sc_out<bool> y_valid{"y_valid"};
  sc_core::sc_in<bool> y_ready{"y_ready"};
  sc_core::sc_out<std::uint32_t> y_data{"y_data"};
  sc_core::sc_out<bool> y_last{"y_last"};

  SC_HAS_PROCESS(SectoralIsmModule);
  explicit SectoralIsmModule(const sc_core::sc_module_name& name) : sc_core::sc_module(name) {
    SC_CTHREAD(run, clk.pos());
    reset_signal_is(rst_n, false);
  }

 private:
  // The RTL's registers (sectoral_ism.sv, sectoral_ism_stream.sv, spill_register.sv).
  struct State {
    bool engine_idle = true;
    std::uint64_t engine_left = 0;  // set-up cycles still to run, the current one included
    std::array<bool, 2> full{};     // index banks
    int wb = 0, rb = 0;             // bank being written / read
    int cell = 0;                   // next cell of bank rb to read
    bool s1_valid = false, s1_last = false;
    std::int16_t s1_index = 0;
    bool a_full = false, b_full = false;   // spill register
    std::uint32_t a_data = 0, b_data = 0;  // {last, index}
  };
  State s_;
  std::int16_t bank_[2][kCells] = {};

  static constexpr std::uint32_t kIndexMask = (1u << Config::index_bits) - 1;

  void write_outputs() {
    z_ready.write(s_.engine_idle && !s_.full[s_.wb]);
    y_valid.write(s_.a_full);
    y_data.write(s_.a_data & kIndexMask);
    y_last.write(((s_.a_data >> Config::index_bits) & 1u) != 0);
  }

  // One clock edge: the next state from the current state and this cycle's inputs.
  void step(bool zv, std::uint32_t zd, bool yr) {
    const State o = s_;
    State n = o;
    const bool z_fire = zv && o.engine_idle && !o.full[o.wb];
    // Set-up engine.
    if (o.engine_idle) {
      if (z_fire) {
        const std::uint32_t reading = zd & ((1u << Config::reading_bits) - 1);
        hls::sectoral_ism_kernel<Config>(reading, bank_[o.wb]);
        n.engine_idle = false;
        n.engine_left = sectoral_ism_setup_cycles<Config>(reading);
      }
    } else if (o.engine_left == 1) {  // the set-up's last cycle: the bank is written
      n.full[o.wb] = true;
      n.wb = 1 - o.wb;
      n.engine_idle = true;
    } else {
      --n.engine_left;
    }
    // Streamer: stage 1 and the spill register.
    const bool sp_ready = !o.b_full;
    const bool s1_advance = !o.s1_valid || sp_ready;
    const bool issue = o.full[o.rb] && s1_advance;
    if (issue) {
      const bool last = o.cell == kCells - 1;
      n.s1_valid = true;
      n.s1_last = last;
      n.s1_index = bank_[o.rb][o.cell];
      if (last) {
        n.cell = 0;
        n.full[o.rb] = false;
        n.rb = 1 - o.rb;
      } else {
        n.cell = o.cell + 1;
      }
    } else if (s1_advance) {
      n.s1_valid = false;
    }
    const std::uint32_t sp_in =
        (std::uint32_t(o.s1_last) << Config::index_bits) |
        (static_cast<std::uint32_t>(static_cast<std::int32_t>(o.s1_index)) & kIndexMask);
    const bool a_drain = o.a_full && yr;
    const bool a_fill = o.s1_valid && sp_ready && (!o.a_full || a_drain) && !o.b_full;
    const bool b_fill = o.s1_valid && sp_ready && o.a_full && !a_drain;
    const bool b_drain = o.b_full && (!o.a_full || a_drain);
    if (b_drain)
      n.a_data = o.b_data;
    else if (a_fill)
      n.a_data = sp_in;
    n.a_full = b_drain || a_fill || (o.a_full && !a_drain);
    if (b_fill) n.b_data = sp_in;
    n.b_full = b_fill || (o.b_full && !b_drain);
    s_ = n;
  }

  void run() {
    s_ = State{};
    write_outputs();
    z_ready.write(false);  // low from a reset edge to the next edge (rtl: out_of_reset_q)
    wait();
    while (true) {
      step(z_valid.read(), z_data.read(), y_ready.read());
      write_outputs();
      wait();
    }
  }
};

}  // namespace intgrid::sc
