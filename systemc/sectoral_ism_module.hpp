// Cycle-accurate SystemC model of the sectoral ISM kernel (rtl/sectoral_ism.sv): the same
// ports, the same micro-architecture and the same cycle of every handshake and every index RAM
// write as the RTL. Three processes, as the RTL's blocks:
//   setup    SectoralIsmSetup (systemc/sectoral_ism_setup.hpp): the set-up engine, which
//            writes the (ring, sector) indices of a reading's window into bank wb
//   banks    one SC_CTHREAD: the two-bank index RAM, its full flags and window registers,
//            and the streamer (rtl/sectoral_ism_stream.sv: ring-major read, stage 1 with the
//            constants of the rings outside the window, spill register)
//   accept   one SC_METHOD: z_ready = out of reset, the engine is idle and its next bank is
//            free, and the engine's start, as the RTL's assigns
// The threads reset while rst_n is low (synchronous, like the RTL); every output is a
// register or a function of registers.
//
//   z_valid/z_ready/z_data/z_last  one reading per beat (z_data: reading_bits wide; z_last
//                                  ignored)
//   y_valid/y_ready/y_data/y_last  one cell index per beat (index_bits two's complement),
//                                  ring-major, y_last on each reading's last cell
#pragma once

#include <array>
#include <cstdint>

#include <systemc>

#include "systemc/sectoral_ism_setup.hpp"

namespace intgrid::sc {

template <class Config>
struct SectoralIsmModule : sc_core::sc_module {
  static constexpr int kCells = Config::rings * Config::bins;
  static constexpr int kRingBits = Config::rings > 1 ? sectoral_ism_clog2(Config::rings) : 1;
  static constexpr int kBankBits = kRingBits + SectoralIsmSetup<Config>::kSectorBits;  // IDX_AW

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

  // The index RAM's write port in this cycle: the address is {bank, ring index, sector}.
  struct IndexRamWrite {
    bool we = false;
    std::uint32_t addr = 0, data = 0;
  };
  IndexRamWrite index_ram_write() const {
    return {idx_we_.read(), (std::uint32_t(wb_.read()) << kBankBits) | idx_waddr_.read(),
            idx_wdata_.read()};
  }

  SC_HAS_PROCESS(SectoralIsmModule);
  explicit SectoralIsmModule(const sc_core::sc_module_name& name) : sc_core::sc_module(name) {
    setup_.clk(clk);
    setup_.rst_n(rst_n);
    setup_.start(start_);
    setup_.z(z_data);
    setup_.idle(idle_);
    setup_.done(done_);
    setup_.r_lo(r_lo_);
    setup_.r_hi(r_hi_);
    setup_.below(below_);
    setup_.idx_we(idx_we_);
    setup_.idx_waddr(idx_waddr_);
    setup_.idx_wdata(idx_wdata_);
    SC_CTHREAD(banks, clk.pos());
    reset_signal_is(rst_n, false);
    SC_METHOD(accept);
    sensitive << out_of_reset_ << z_valid << idle_ << bank_free_;
  }

 private:
  SectoralIsmSetup<Config> setup_{"setup"};
  sc_core::sc_signal<bool> start_{"start"}, idle_{"idle"}, done_{"done"};
  sc_core::sc_signal<int> r_lo_{"r_lo"}, r_hi_{"r_hi"}, below_{"below"};
  sc_core::sc_signal<bool> idx_we_{"idx_we"};
  sc_core::sc_signal<std::uint32_t> idx_waddr_{"idx_waddr"}, idx_wdata_{"idx_wdata"};
  sc_core::sc_signal<bool> bank_free_{"bank_free"};  // !full[wb]
  sc_core::sc_signal<bool> wb_{"wb"};
  // Low from a reset edge to the first edge out of reset (rtl: out_of_reset_q).
  sc_core::sc_signal<bool> out_of_reset_{"out_of_reset"};

  void accept() {
    const bool ready = out_of_reset_.read() && idle_.read() && bank_free_.read();
    z_ready.write(ready);
    start_.write(z_valid.read() && ready);
  }

  // The RTL's registers of sectoral_ism.sv, sectoral_ism_stream.sv and spill_register.sv.
  static constexpr int kBps = Config::bins_per_sector;
  struct State {
    std::array<bool, 2> full{};  // index banks
    int wb = 0, rb = 0;          // bank being written / read
    std::array<int, 2> lo{}, hi{}, below{};
    int ring = 0, sec = 0, bin = 0;  // the next cell to read
    std::uint32_t rdata = 0;         // the RAM's registered read
    bool s1_valid = false, s1_last = false, s1_const = false;
    std::uint32_t s1_const_idx = 0;
    bool a_full = false, b_full = false;   // spill register
    std::uint32_t a_data = 0, b_data = 0;  // {last, index}
  };
  State s_;
  std::array<std::uint32_t, std::size_t{2} << kBankBits> ram_{};

  static constexpr std::uint32_t kIndexMask = (1u << Config::index_bits) - 1;

  void write_outputs() {
    bank_free_.write(!s_.full[static_cast<std::size_t>(s_.wb)]);
    wb_.write(s_.wb != 0);
    y_valid.write(s_.a_full);
    y_data.write(s_.a_data & kIndexMask);
    y_last.write(((s_.a_data >> Config::index_bits) & 1u) != 0);
  }

  // One clock edge: the next state from the current state and this cycle's inputs.
  void step(bool yr) {
    const State o = s_;
    State n = o;
    // Banks: the engine's last set-up cycle.
    if (done_.read()) {
      const auto w = static_cast<std::size_t>(o.wb);
      n.full[w] = true;
      n.wb = 1 - o.wb;
      n.lo[w] = r_lo_.read();
      n.hi[w] = r_hi_.read();
      n.below[w] = below_.read();
    }
    // Streamer: stage 1 reads the next cell (or takes a constant) while it can advance.
    const auto r = static_cast<std::size_t>(o.rb);
    const bool sp_ready = !o.b_full;
    const bool s1_advance = !o.s1_valid || sp_ready;
    const bool issue = o.full[r] && s1_advance;
    const bool last_cell =
        o.ring == Config::rings - 1 && o.sec == Config::sectors - 1 && o.bin == kBps - 1;
    if (issue) {
      const bool below = o.ring + 1 < o.lo[r];
      const bool above = o.ring + 1 > o.hi[r];
      n.rdata =
          ram_[(r << kBankBits) | (std::size_t(o.ring) << SectoralIsmSetup<Config>::kSectorBits) |
               std::size_t(o.sec)];
      n.s1_valid = true;
      n.s1_last = last_cell;
      n.s1_const = below || above;
      n.s1_const_idx = below ? static_cast<std::uint32_t>(o.below[r]) & kIndexMask : 0;
      n.bin = o.bin + 1;
      if (o.bin == kBps - 1) {
        n.bin = 0;
        n.sec = o.sec + 1;
        if (o.sec == Config::sectors - 1) {
          n.sec = 0;
          n.ring = last_cell ? 0 : o.ring + 1;
        }
      }
      if (last_cell) {  // the bank is read: free it
        n.full[r] = false;
        n.rb = 1 - o.rb;
      }
    } else if (s1_advance) {
      n.s1_valid = false;
    }
    // Spill register.
    const std::uint32_t sp_in =
        (std::uint32_t(o.s1_last) << Config::index_bits) | (o.s1_const ? o.s1_const_idx : o.rdata);
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
    // The engine's write, after the read (a read of the address written returns old data).
    if (idx_we_.read())
      ram_[(std::size_t(o.wb) << kBankBits) | idx_waddr_.read()] = idx_wdata_.read();
    s_ = n;
  }

  void banks() {
    s_ = State{};
    write_outputs();
    out_of_reset_.write(false);
    wait();
    out_of_reset_.write(true);
    while (true) {
      step(y_ready.read());
      write_outputs();
      wait();
    }
  }
};

}  // namespace intgrid::sc
