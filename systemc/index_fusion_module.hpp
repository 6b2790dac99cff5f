// Kernel 1, index fusion (S_eps), as a cycle-accurate SystemC model of rtl/index_fusion.sv.
//
// Same ports (names, directions, widths), same registers and same handshake timing as the RTL, so
// a co-simulation can compare the two cycle by cycle:
// - one SC_CTHREAD on clk_i.pos() with a synchronous active-low reset (rst_ni) holds the state of
//   the RTL's spill_register: two entries (a faces the output, b catches a beat that arrives while
//   a is stalled), each {last, data}; y_valid_o, y_data_o and y_last_o are driven from entry a;
// - the input ready is combinational in the RTL (a_ready_o = b_ready_o = a_valid_i && b_valid_i &&
//   !b_full_q && rst_ni, the join of the two streams), so a small SC_METHOD computes it from the
//   input valids, the reset and the registered b_full_q, exactly as the RTL's assigns do; it never
//   depends on y_ready_i.
// The data path is the HLS function hls::fuse_beat, called when a beat enters the buffer (in the
// RTL the adders sit between the inputs and the spill register).
//
// y_last_o follows a_last_i; b_last_i is ignored (see rtl/index_fusion.sv).
#pragma once

#include <algorithm>
#include <cstddef>

#include <systemc>

#include "hls/index_fusion.hpp"

namespace intgrid::sc {

template <int B, int LANES>
struct IndexFusionModule : ::sc_core::sc_module {
  static constexpr int kWidth = B * LANES;
  using Data = ::sc_dt::sc_biguint<kWidth>;
  using HlsBeat = hls::Beat<B, LANES>;

  ::sc_core::sc_in<bool> clk_i{"clk_i"};
  ::sc_core::sc_in<bool> rst_ni{"rst_ni"};  // synchronous, active low
  // input stream a
  ::sc_core::sc_in<bool> a_valid_i{"a_valid_i"};
  ::sc_core::sc_out<bool> a_ready_o{"a_ready_o"};
  ::sc_core::sc_in<Data> a_data_i{"a_data_i"};
  ::sc_core::sc_in<bool> a_last_i{"a_last_i"};
  // input stream b
  ::sc_core::sc_in<bool> b_valid_i{"b_valid_i"};
  ::sc_core::sc_out<bool> b_ready_o{"b_ready_o"};
  ::sc_core::sc_in<Data> b_data_i{"b_data_i"};
  ::sc_core::sc_in<bool> b_last_i{"b_last_i"};
  // output stream y
  ::sc_core::sc_out<bool> y_valid_o{"y_valid_o"};
  ::sc_core::sc_in<bool> y_ready_i{"y_ready_i"};
  ::sc_core::sc_out<Data> y_data_o{"y_data_o"};
  ::sc_core::sc_out<bool> y_last_o{"y_last_o"};

  SC_HAS_PROCESS(IndexFusionModule);
  explicit IndexFusionModule(const ::sc_core::sc_module_name& name) : ::sc_core::sc_module(name) {
    SC_CTHREAD(run, clk_i.pos());
    reset_signal_is(rst_ni, false);
    SC_METHOD(join);
    sensitive << rst_ni << a_valid_i << b_valid_i << b_full_q_;
  }

  // Conversions between the bus and the HLS beat (same packing: bus bit i = word i/64, bit i%64).
  static HlsBeat to_beat(const Data& data) {
    HlsBeat beat{};
    for (int w = 0; w < hls::IndexBeat<B, LANES>::kWords; ++w) {
      const int lo = 64 * w;
      const int hi = std::min(kWidth, lo + 64) - 1;
      beat[static_cast<std::size_t>(w)] = data.range(hi, lo).to_uint64();
    }
    return beat;
  }
  static Data to_data(const HlsBeat& beat) {
    Data data = 0;
    for (int w = 0; w < hls::IndexBeat<B, LANES>::kWords; ++w) {
      const int lo = 64 * w;
      const int hi = std::min(kWidth, lo + 64) - 1;
      data.range(hi, lo) = beat[static_cast<std::size_t>(w)];
    }
    return data;
  }

 private:
  // The spill register's state, as in rtl/spill_register.sv.
  ::sc_core::sc_signal<bool> b_full_q_{"b_full_q"};  // also read by the combinational join
  bool a_full_q_ = false;
  Data a_data_q_ = 0, b_data_q_ = 0;
  bool a_last_q_ = false, b_last_q_ = false;

  // The join: out of reset, both halves of the beat present and room in the buffer (rtl: fire).
  void join() {
    const bool fire = rst_ni.read() && a_valid_i.read() && b_valid_i.read() && !b_full_q_.read();
    a_ready_o.write(fire);
    b_ready_o.write(fire);
  }

  void run() {
    // Reset (rst_ni low at a rising edge): both entries empty, data cleared.
    a_full_q_ = false;
    a_data_q_ = 0;
    b_data_q_ = 0;
    a_last_q_ = false;
    b_last_q_ = false;
    b_full_q_.write(false);
    drive_outputs();
    // No local lives across wait(): a suspended thread's stack is never unwound at the end of the
    // simulation, and LeakSanitizer would report the digits of an sc_biguint left on it.
    while (true) {
      wait();
      clock_edge();
    }
  }

  // One rising edge out of reset: the spill register's always_ff. Everything read here holds the
  // value settled before the edge.
  void clock_edge() {
    const bool b_full_q = b_full_q_.read();
    const bool fire = a_valid_i.read() && b_valid_i.read() && !b_full_q;
    const bool a_drain = a_full_q_ && y_ready_i.read();                // a's beat leaves
    const bool a_fill = fire && (!a_full_q_ || a_drain) && !b_full_q;  // input goes to a
    const bool b_fill = fire && a_full_q_ && !a_drain;                 // a stalls: input to b
    const bool b_drain = b_full_q && (!a_full_q_ || a_drain);          // b moves up into a

    Data in_data = 0;
    bool in_last = false;
    if (a_fill || b_fill) {
      in_data =
          to_data(hls::fuse_beat<B, LANES>(to_beat(a_data_i.read()), to_beat(b_data_i.read())));
      in_last = a_last_i.read();
    }
    if (b_drain) {
      a_data_q_ = b_data_q_;
      a_last_q_ = b_last_q_;
    } else if (a_fill) {
      a_data_q_ = in_data;
      a_last_q_ = in_last;
    }
    a_full_q_ = b_drain || a_fill || (a_full_q_ && !a_drain);
    if (b_fill) {
      b_data_q_ = in_data;
      b_last_q_ = in_last;
    }
    b_full_q_.write(b_fill || (b_full_q && !b_drain));
    drive_outputs();
  }

  void drive_outputs() {
    y_valid_o.write(a_full_q_);
    y_data_o.write(a_data_q_);
    y_last_o.write(a_last_q_);
  }
};

}  // namespace intgrid::sc
