#include "testbench/cortex_m3/platform.hpp"

namespace intgrid::cortex_m3 {
namespace {

// CMSDK APB timer (Arm DDI 0479): a 32-bit down-counter at PCLK (25 MHz on mps2-an385). In
// QEMU's model it raises its interrupt on 1 -> 0, holds 0 for one tick, then reloads: a period
// is RELOAD + 1 ticks.
struct CmsdkApbTimer {
  volatile std::uint32_t ctrl;
  volatile std::uint32_t value;
  volatile std::uint32_t reload;
  volatile std::uint32_t intstatus;  // bit 0; write 1 to clear
};
constexpr std::uint32_t timer_enable = 1u << 0;
constexpr std::uint32_t timer_interrupt_enable = 1u << 3;
constexpr std::uintptr_t timer0_address = 0x40000000;
constexpr unsigned timer0_irq = 8;
constexpr std::uintptr_t nvic_iser0_address = 0xE000E100;

CmsdkApbTimer& timer0() {
  return *reinterpret_cast<CmsdkApbTimer*>(timer0_address);
}

// The first period is short (2^21 ticks, 84 M instructions) so that every run longer than
// that crosses a wrap: the wrap path is exercised routinely, not only after 172 G instructions.
constexpr std::uint32_t ticks_to_first_wrap = 1u << 21;

volatile std::uint32_t timer_wraps = 0;

// Ticks since start_instruction_counter(). The phase within a period is -VALUE mod 2^32: it
// restarts from 0 on the 1 -> 0 step, where the interrupt counts a wrap. The first period
// starts at phase 2^32 - ticks_to_first_wrap.
std::uint64_t timer_ticks() {
  std::uint32_t primask;
  asm volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
  std::uint32_t wraps = timer_wraps;
  std::uint32_t value = timer0().value;
  if (timer0().intstatus & 1u) {
    // Wrapped before the handler could run: VALUE read again is surely past the wrap.
    value = timer0().value;
    ++wraps;
  }
  asm volatile("msr primask, %0" ::"r"(primask) : "memory");
  const std::uint64_t phase = (std::uint64_t{wraps} << 32) | static_cast<std::uint32_t>(0u - value);
  return phase - ((std::uint64_t{1} << 32) - ticks_to_first_wrap);
}

// Returns just after the timer's next tick: regions started right after it start at the same
// phase of a tick, so their counts differ by their instructions' difference, within a tick.
void wait_for_tick() {
  const std::uint32_t value = timer0().value;
  while (timer0().value == value) {
  }
}

}  // namespace

extern "C" void timer0_irq_handler() {
  timer_wraps = timer_wraps + 1;
  timer0().intstatus = 1u;
}

void start_instruction_counter() {
  CmsdkApbTimer& timer = timer0();
  timer.ctrl = 0;
  timer.reload = 0xFFFFFFFFu;  // a period of 2^32 ticks (this also loads VALUE)
  timer.value = ticks_to_first_wrap;
  timer.intstatus = 1u;
  *reinterpret_cast<volatile std::uint32_t*>(nvic_iser0_address) = 1u << timer0_irq;
  timer.ctrl = timer_enable | timer_interrupt_enable;
}

// Not inlined, so that calibrate() pays the same call as every other caller.
[[gnu::noinline]] std::uint64_t instructions_executed() {
  return timer_ticks() * instructions_per_tick;
}

Calibration calibrate(std::uint32_t iterations) {
  Calibration calibration;
  calibration.iterations = iterations;
  calibration.expected = 2 * std::uint64_t{iterations};

  wait_for_tick();
  const std::uint64_t empty_before = instructions_executed();
  asm volatile("" ::: "memory");
  const std::uint64_t empty_after = instructions_executed();
  calibration.overhead = empty_after - empty_before;
  if (iterations == 0) return calibration;  // the loop below needs at least one iteration

  std::uint32_t counter = iterations;
  wait_for_tick();
  const std::uint64_t before = instructions_executed();
  asm volatile(
      "1: subs %0, %0, #1\n\t"
      "bne 1b"
      : "+l"(counter)
      :
      : "cc");
  const std::uint64_t after = instructions_executed();
  calibration.measured = after - before - calibration.overhead;
  return calibration;
}

}  // namespace intgrid::cortex_m3
