// The cycle schedule of the sectoral ISM micro-architecture (rtl/sectoral_ism_setup.sv) as a
// closed formula: the testbenches' independent oracle of the set-up length and latency
// (SectoralIsmRtl.*SetupCyclesFollowTheSchedule, *FullThroughput). The SystemC model does not
// use it: it runs the schedule phase by phase (systemc/sectoral_ism_setup.hpp). Pure C++.
#pragma once

#include <cstdint>

namespace intgrid::sc {

// The rings r = 1..rings with |z - r * 2^reading_frac_bits| < window_cells cells: the only
// rings whose terms are not log 0. Empty (count 0) for z >= reach.
struct IsmWindow {
  int first = 0;  // r_lo
  int last = -1;  // r_hi
  int count() const { return last >= first ? last - first + 1 : 0; }
};

template <class Config>
constexpr IsmWindow sectoral_ism_window(std::uint32_t reading) {
  const int cells = static_cast<int>(reading >> Config::reading_frac_bits);
  const bool on_ring = (reading & ((1u << Config::reading_frac_bits) - 1)) == 0;
  int lo = cells - Config::window_cells + 1;
  int hi = cells + Config::window_cells - (on_ring ? 1 : 0);
  lo = lo < 1 ? 1 : lo;
  hi = hi > Config::rings ? Config::rings : hi;
  return IsmWindow{lo, hi};
}

// Set-up cycles of one reading: from the cycle after it is accepted to the last set-up cycle,
// inclusive. 2 with an empty window; else, n rings in the window, ND multiplier digits,
// V conditions, C classes, Ns sectors:
//   init 3 + ND, rings (n + 1) V C + 4, suffix 2 n + 2, prefix 1 + n (3 Ns + 1) + 4, done 1.
template <class Config>
constexpr std::uint64_t sectoral_ism_setup_cycles(std::uint32_t reading) {
  const std::uint64_t n = static_cast<std::uint64_t>(sectoral_ism_window<Config>(reading).count());
  if (n == 0) return 2;
  const std::uint64_t slot = std::uint64_t(Config::conditions) * Config::classes;
  return std::uint64_t(Config::mul_digits) + 15 + (n + 1) * slot + 2 * n +
         n * (3 * std::uint64_t(Config::sectors) + 1);
}

// Cycles from the set-up's last cycle to the reading's first cell on y_valid, when the
// streamer is free: bank flag, RAM read, spill register.
inline constexpr std::uint64_t kSectoralIsmStreamLatency = 3;

}  // namespace intgrid::sc
