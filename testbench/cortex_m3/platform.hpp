// The bare-metal platform of the Cortex-M3 firmware, run under
//   qemu-system-arm -M mps2-an385 -icount shift=0 -semihosting-config enable=on,target=native
// Instruction counting, its calibration, and allocation counting. Printing is newlib's printf
// over semihosting; main's return value becomes QEMU's exit status.
#pragma once

#include <cstddef>
#include <cstdint>

namespace intgrid::cortex_m3 {

// -icount shift=0 advances QEMU's virtual clock by exactly 1 ns per executed instruction; the
// counter is the board's CMSDK APB timer 0, which QEMU clocks at 25 MHz: 40 ns per tick.
inline constexpr std::uint32_t instructions_per_tick = 40;

// Starts the counter. The reset handler calls it before the static constructors.
void start_instruction_counter();

// Instructions executed since start_instruction_counter(), a multiple of instructions_per_tick:
// the difference of two readings is within one tick (40 instructions) of the true count.
// 64-bit: the 32-bit timer's wraps (every 2^32 ticks, 172 G instructions) are counted.
std::uint64_t instructions_executed();

// operator new calls (every form) since reset, and operator delete calls on non-null pointers:
// a region that must not allocate keeps allocations() unchanged.
std::size_t allocations();
std::size_t deallocations();

// Bytes of the heap region malloc has taken so far (newlib's malloc does not give them back):
// the program's peak heap, to within malloc's bookkeeping.
std::size_t heap_bytes();

// Instructions and allocations of one call of `region`. The instructions include the
// counter's own cost, about 30 instructions: an empty region counts 0 or 40.
struct RegionCost {
  std::uint64_t instructions = 0;
  std::size_t allocations = 0;
};
template <class Region>
RegionCost measure(Region&& region) {
  const std::size_t allocations_before = allocations();
  const std::uint64_t before = instructions_executed();
  region();
  const std::uint64_t after = instructions_executed();
  return {after - before, allocations() - allocations_before};
}

// A count-down loop of exactly 2 * iterations instructions (subs, bne), counted with
// instructions_executed(), less the counter's own cost (an empty region counted alike).
struct Calibration {
  std::uint32_t iterations = 0;
  std::uint64_t expected = 0;  // 2 * iterations
  std::uint64_t measured = 0;
  std::uint64_t overhead = 0;  // the empty region's count (0 or 40), subtracted from measured
  std::int64_t error() const {
    return static_cast<std::int64_t>(measured) - static_cast<std::int64_t>(expected);
  }
};
Calibration calibrate(std::uint32_t iterations);

}  // namespace intgrid::cortex_m3
