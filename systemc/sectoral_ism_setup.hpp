// Cycle-accurate SystemC model of the sectoral ISM's set-up engine (rtl/sectoral_ism_setup.sv):
// the same phases, the same counters and the same pipelines, register for register where a
// register decides when something happens, so that every index RAM write (we, address, data)
// happens in the RTL's cycle. The values come from the HLS per-step helpers of
// hls/sectoral_ism.hpp (ism_log_density, ism_log_mul, ism_log_add, ism_index_of_log_odds),
// applied where the RTL's units apply them, and travel down the units' pipeline registers:
//   density unit   product c of a slot done in slot cycle ND + 4 + c ND (digit-serial
//                  multiplier); the densities switch to the next ring in slot cycle 0
//   sum pipeline   fetch (weight[v][c], slot cycle c V + v), multiply, add into accumulator v
//                  (the V accumulators interleaved: each comes back every V cycles through the
//                  log-add unit's 2 stages and a (V - 2)-deep result history), times the prior
//   log-add unit   2 stages; index unit 3 stages and the write register
//   small RAMs     T_r, the conditioned sums and the suffix sums, registered reads
// The multiplier's digits of e * e (phase Square) are counted, not computed: ism_log_density
// takes the reading and the ring, where the RTL steps e and e^2 from ring to ring.
//
// One SC_CTHREAD on clk.pos(), reset while rst_n is low (synchronous). Every output is a
// register or a function of registers, written after each edge. Log values are the HLS's
// int32_t with Config::log_zero for log 0 (the RTL's {zero, value} pair).
//
//   start, z                 a reading is accepted (only while idle)
//   idle, done               the engine waits for a reading; the set-up's last cycle
//   r_lo, r_hi, below        the window's rings (r_lo = rings + 1 if empty) and the index of
//                            the rings before it
//   idx_we/idx_waddr/wdata   the index RAM write: address {ring index, sector}, data the
//                            index in index_bits two's complement
#pragma once

#include <array>
#include <cstdint>

#include <systemc>

#include "hls/sectoral_ism.hpp"

namespace intgrid::sc {

constexpr int sectoral_ism_clog2(int n) {
  int bits = 0;
  while ((1 << bits) < n) ++bits;
  return bits;
}

template <class Config>
struct SectoralIsmSetup : sc_core::sc_module {
  static constexpr int R = Config::rings;
  static constexpr int Ns = Config::sectors;
  static constexpr int C = Config::classes;
  static constexpr int V = Config::conditions;
  static constexpr int ND = Config::mul_digits;
  static constexpr int kSlot = V * C;             // L_A: cycles of a ring slot
  static constexpr int kPrefixRing = 3 * Ns + 1;  // L_C: cycles of a prefix ring
  static constexpr int kHistory = V - 2;          // SR_D: the accumulator loop's history
  static constexpr int kSectorBits = Ns > 1 ? sectoral_ism_clog2(Ns) : 1;  // J_W
  static constexpr std::int32_t Z = Config::log_zero;
  static_assert(V == 2 * Ns + 1, "one total and two sums per sector");
  static_assert(C * ND + 4 < kSlot, "a slot's densities are done before the next slot");

  sc_core::sc_in<bool> clk{"clk"};
  sc_core::sc_in<bool> rst_n{"rst_n"};
  sc_core::sc_in<bool> start{"start"};
  sc_core::sc_in<std::uint32_t> z{"z"};
  sc_core::sc_out<bool> idle{"idle"};
  sc_core::sc_out<bool> done{"done"};
  sc_core::sc_out<int> r_lo{"r_lo"};
  sc_core::sc_out<int> r_hi{"r_hi"};
  sc_core::sc_out<int> below{"below"};
  sc_core::sc_out<bool> idx_we{"idx_we"};
  sc_core::sc_out<std::uint32_t> idx_waddr{"idx_waddr"};
  sc_core::sc_out<std::uint32_t> idx_wdata{"idx_wdata"};

  SC_HAS_PROCESS(SectoralIsmSetup);
  explicit SectoralIsmSetup(const sc_core::sc_module_name& name) : sc_core::sc_module(name) {
    SC_CTHREAD(run, clk.pos());
    reset_signal_is(rst_n, false);
  }

 private:
  enum class Phase {
    Idle,
    Init,
    Error,
    Square,
    Rings,
    RingsDrain,
    Suffix,
    PrefixFetch,
    Prefix,
    PrefixDrain,
    Done
  };
  // What a log-add result is for (the RTL's tag kinds).
  enum class Use { None, Sum, SumLast, After, Total, Before, Den };
  struct Tag {
    Use use = Use::None;
    int sel = 0;   // condition v (rings), sector j (den)
    int ring = 0;  // ring index r - 1
  };
  struct LogAdd {  // a log-add pipeline register
    bool valid = false;
    std::int32_t value = 0;
    Tag tag;
  };
  struct IndexWrite {  // an index unit pipeline register
    bool valid = false;
    int index = 0;
    std::uint32_t addr = 0;
  };

  // The RTL's registers and memories.
  struct State {
    Phase phase = Phase::Idle;
    int cyc = 0;  // cycle within the phase or slot
    int k = 0;    // slot / prefix ring
    std::uint32_t z = 0;
    int r_lo = 0, r_hi = 0, n_win = 0;
    std::int32_t before_cur = 0, before_nxt = 0, beyond = 0, total = 0;
    // Density unit: the densities being computed and those the sum pipeline reads.
    std::array<std::int32_t, C> dens_next{}, dens_cur{};
    // Sum pipeline: fetch counters, M and A stages.
    int sp_c = 0, sp_v = 0;
    bool m_valid = false, m_first = false, m_last = false;
    int m_c = 0, m_v = 0, m_ring = 0;
    std::int32_t m_weight = 0;
    bool a_valid = false, a_first = false, a_last = false;
    int a_v = 0, a_ring = 0;
    std::int32_t a_b = 0;
    // Log-add unit (stage 1, result) and the result history (history[0] the oldest).
    LogAdd s1, res;
    std::array<std::int32_t, kHistory> history{};
    // Store stage of the ring sums.
    bool st_we = false, st_is_t = false;
    int st_ring = 0, st_cj = 0;
    std::int32_t st_data = 0;
    // T_r, the conditioned sums (per ring: Ns occupied, then Ns emptied) and the suffix sums,
    // with their registered read data.
    std::array<std::int32_t, R> t_ram{}, after_ram{};
    std::array<std::array<std::int32_t, 2 * Ns>, R> cond_ram{};
    std::int32_t t_rdata = 0, after_rdata = 0, cond_rdata = 0;
    // Index unit stages X1, X2 and the write register.
    IndexWrite x1, x2, write;
  };
  State s_;

  static constexpr std::int32_t kTwo = std::int32_t{1} << Config::log_frac_bits;  // log2(2)

  void write_outputs() {
    idle.write(s_.phase == Phase::Idle);
    done.write(s_.phase == Phase::Done);
    r_lo.write(s_.r_lo);
    r_hi.write(s_.r_hi);
    // A ring before the window: num = log 0, den = 2 * (the sum of every window ring's T).
    below.write(hls::ism_index_of_log_odds<Config>(Z, hls::ism_log_mul<Config>(kTwo, s_.total)));
    idx_we.write(s_.write.valid);
    idx_waddr.write(s_.write.addr);
    idx_wdata.write(static_cast<std::uint32_t>(s_.write.index) & ((1u << Config::index_bits) - 1));
  }

  // The window [r_lo, r_hi]: the rings with |z - r| < window_cells cells (SInit).
  static void window(std::uint32_t reading, int& lo, int& hi) {
    const int cells = static_cast<int>(reading >> Config::reading_frac_bits);
    const bool on_ring = (reading & ((1u << Config::reading_frac_bits) - 1)) == 0;
    lo = cells - Config::window_cells + 1;
    hi = cells + Config::window_cells - (on_ring ? 1 : 0);
    lo = lo < 1 ? 1 : lo > R + 1 ? R + 1 : lo;
    hi = hi > R ? R : hi;
  }

  // One clock edge: the next state from the current state and this cycle's inputs.
  void step(bool start_now, std::uint32_t z_now) {
    const State& o = s_;
    State n = o;
    const bool rings = o.phase == Phase::Rings;
    const bool prefix = o.phase == Phase::Prefix;
    const bool slot_end = rings && o.cyc == kSlot - 1;
    const bool prefix_last_cycle = prefix && o.cyc == kPrefixRing - 1;
    const bool prefix_last_ring = o.k == o.n_win - 1;
    const int m_step = o.cyc >> 1;  // suffix step
    const bool suffix_step = o.phase == Phase::Suffix && m_step < o.n_win;
    const bool b_fetch = suffix_step && (o.cyc & 1) == 0;
    const bool b_issue = suffix_step && (o.cyc & 1) == 1;
    const int p_ring = o.r_lo - 1 + o.k;  // prefix ring index

    // Density unit: slot k computes ring r_lo + k (if there is one) while the sum pipeline
    // reads ring r_lo + k - 1's densities, switched in at the slot's first cycle.
    if (rings && o.cyc == 0) n.dens_cur = o.dens_next;
    if (rings && o.k != o.n_win) {
      const int c = (o.cyc - ND - 4) / ND;
      if (o.cyc >= ND + 4 && (o.cyc - ND - 4) % ND == 0 && c < C)
        n.dens_next[static_cast<std::size_t>(c)] =
            hls::ism_log_density<Config>(o.z, o.r_lo + o.k, c);
    }

    // Sum pipeline: fetch step c V + v of slot k (ring r_lo + k - 1), multiply, add.
    const bool f_valid = rings && o.k != 0;
    if (!rings || slot_end) {
      n.sp_c = 0;
      n.sp_v = 0;
    } else if (o.sp_v == V - 1) {
      n.sp_c = o.sp_c + 1;
      n.sp_v = 0;
    } else {
      n.sp_v = o.sp_v + 1;
    }
    n.m_valid = f_valid;
    n.m_c = o.sp_c;
    n.m_v = o.sp_v;
    n.m_first = o.sp_c == 0;
    n.m_last = o.sp_c == C - 1;
    n.m_ring = o.r_lo + o.k - 2;
    n.m_weight = Config::log_weight[static_cast<std::size_t>(o.sp_v * C + o.sp_c)];
    n.a_valid = o.m_valid;
    n.a_v = o.m_v;
    n.a_first = o.m_first;
    n.a_last = o.m_last;
    n.a_ring = o.m_ring;
    n.a_b = hls::ism_log_mul<Config>(o.dens_cur[static_cast<std::size_t>(o.m_c)], o.m_weight);

    // The log-add unit's operands, by phase.
    LogAdd in;
    std::int32_t a = o.before_cur, b = o.cond_rdata;
    in.tag.ring = p_ring;
    switch (o.phase) {
      case Phase::Rings:
      case Phase::RingsDrain:
        in.valid = o.a_valid;
        a = o.a_first ? Z : o.history[0];  // accumulator v, V cycles old
        b = o.a_b;
        in.tag = Tag{o.a_last ? Use::SumLast : Use::Sum, o.a_v, o.a_ring};
        break;
      case Phase::Suffix:  // after[r - 1] = after[r] + T_r, downward from r_hi
        in.valid = b_issue;
        a = m_step == 0 ? Z : o.res.value;
        b = o.t_rdata;
        in.tag = Tag{m_step == o.n_win - 1 ? Use::Total : Use::After, 0, o.r_hi - 2 - m_step};
        break;
      case Phase::Prefix:  // before + T_r; e_j, then num_j; den_j = e_j + 2 after[r]
        in.valid = true;
        if (o.cyc == 0) {
          b = o.t_rdata;
          in.tag.use = Use::Before;
        } else if (o.cyc > 2 * Ns) {
          a = Ns > 1 ? o.history[1] : o.res.value;  // e_j, 2 Ns - 2 cycles old
          b = o.beyond;
          in.tag.use = Use::Den;
          in.tag.sel = o.cyc - (2 * Ns + 1);
        }
        break;
      default:
        break;
    }
    n.s1 = LogAdd{in.valid, hls::ism_log_add<Config>(a, b), in.tag};
    n.res = o.s1;
    for (int i = 0; i + 1 < kHistory; ++i)
      n.history[static_cast<std::size_t>(i)] = o.history[static_cast<std::size_t>(i + 1)];
    n.history[kHistory - 1] = o.res.value;

    // Store: T_r or a conditioned sum, times the ring prior 2^-((r - 1) bins).
    n.st_we = o.res.valid && o.res.tag.use == Use::SumLast;
    n.st_is_t = o.res.tag.sel == 0;
    n.st_ring = o.res.tag.ring;
    n.st_cj = o.res.tag.sel - 1;
    n.st_data = hls::ism_log_mul<Config>(
        o.res.value, -((o.res.tag.ring * Config::bins) << Config::log_frac_bits));
    if (o.st_we && o.st_is_t) n.t_ram[static_cast<std::size_t>(o.st_ring)] = o.st_data;
    if (o.st_we && !o.st_is_t)
      n.cond_ram[static_cast<std::size_t>(o.st_ring)][static_cast<std::size_t>(o.st_cj)] =
          o.st_data;

    // RAM reads: T in the suffix and for each prefix ring, after for each prefix ring, the
    // conditioned sums in a prefix ring's first 2 Ns cycles (emptied, then occupied).
    if (b_fetch) {
      n.t_rdata = o.t_ram[static_cast<std::size_t>(o.r_hi - 1 - m_step)];
    } else if (o.phase == Phase::PrefixFetch) {
      n.t_rdata = o.t_ram[static_cast<std::size_t>(o.r_lo - 1)];
      n.after_rdata = o.after_ram[static_cast<std::size_t>(o.r_lo - 1)];
    } else if (prefix_last_cycle && !prefix_last_ring) {
      n.t_rdata = o.t_ram[static_cast<std::size_t>(p_ring + 1)];
      n.after_rdata = o.after_ram[static_cast<std::size_t>(p_ring + 1)];
    }
    if (prefix && o.cyc < 2 * Ns) {
      const int cj = o.cyc < Ns ? o.cyc + Ns : o.cyc - Ns;
      n.cond_rdata = o.cond_ram[static_cast<std::size_t>(p_ring)][static_cast<std::size_t>(cj)];
    }
    // after: log 0 past the window's last ring, then the suffix sums as they return.
    if (o.phase == Phase::Suffix && o.cyc == 0)
      n.after_ram[static_cast<std::size_t>(o.r_hi - 1)] = Z;
    else if (o.res.valid && o.res.tag.use == Use::After)
      n.after_ram[static_cast<std::size_t>(o.res.tag.ring)] = o.res.value;

    // Index unit: (num_j, Ns cycles old, and den_j) into the index of (ring, sector j).
    const bool den_back = o.res.valid && o.res.tag.use == Use::Den;
    n.x1 = IndexWrite{den_back, hls::ism_index_of_log_odds<Config>(o.history[Ns - 1], o.res.value),
                      (static_cast<std::uint32_t>(o.res.tag.ring) << kSectorBits) |
                          static_cast<std::uint32_t>(o.res.tag.sel)};
    n.x2 = o.x1;
    n.write = o.x2;

    // Registers of the prefix sums and the window total.
    if (o.res.valid && o.res.tag.use == Use::Total) n.total = o.res.value;
    if (o.res.valid && o.res.tag.use == Use::Before) n.before_nxt = o.res.value;
    if (o.phase == Phase::PrefixFetch)
      n.before_cur = Z;
    else if (prefix_last_cycle)
      n.before_cur = o.before_nxt;
    if (prefix && o.cyc == 0) n.beyond = hls::ism_log_mul<Config>(kTwo, o.after_rdata);

    // Control.
    n.cyc = o.cyc + 1;
    switch (o.phase) {
      case Phase::Idle:
        n.cyc = 0;
        if (start_now) {
          n.phase = Phase::Init;
          n.z = z_now;
        }
        break;
      case Phase::Init:
        window(o.z, n.r_lo, n.r_hi);
        n.total = Z;
        n.phase = n.r_lo > n.r_hi ? Phase::Done : Phase::Error;
        break;
      case Phase::Error:
        n.n_win = o.r_hi - o.r_lo + 1;
        n.phase = Phase::Square;
        n.cyc = 0;
        break;
      case Phase::Square:  // the ND digits of e * e, and its 2 pipeline stages
        if (o.cyc == ND) {
          n.phase = Phase::Rings;
          n.cyc = 0;
          n.k = 0;
        }
        break;
      case Phase::Rings:
        if (slot_end) {
          n.cyc = 0;
          if (o.k == o.n_win)
            n.phase = Phase::RingsDrain;
          else
            n.k = o.k + 1;
        }
        break;
      case Phase::RingsDrain:  // the last sums through the multiply, log-add and store stages
        if (o.cyc == 3) {
          n.phase = Phase::Suffix;
          n.cyc = 0;
        }
        break;
      case Phase::Suffix:
        if (o.cyc == 2 * o.n_win + 1) n.phase = Phase::PrefixFetch;
        break;
      case Phase::PrefixFetch:
        n.phase = Phase::Prefix;
        n.cyc = 0;
        n.k = 0;
        break;
      case Phase::Prefix:
        if (prefix_last_cycle) {
          n.cyc = 0;
          if (prefix_last_ring)
            n.phase = Phase::PrefixDrain;
          else
            n.k = o.k + 1;
        }
        break;
      case Phase::PrefixDrain:  // the last den through the log-add and index units
        if (o.cyc == 3) n.phase = Phase::Done;
        break;
      case Phase::Done:
        n.phase = Phase::Idle;
        break;
    }
    s_ = n;
  }

  void run() {
    s_ = State{};
    write_outputs();
    wait();
    while (true) {
      step(start.read(), z.read());
      write_outputs();
      wait();
    }
  }
};

}  // namespace intgrid::sc
