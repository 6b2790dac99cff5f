// Vector table, reset and fault handlers of the Cortex-M3 on QEMU's mps2-an385.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "testbench/cortex_m3/platform.hpp"
#include "testbench/cortex_m3/semihosting.hpp"

extern "C" {

// From mps2_an385.ld.
extern std::uint32_t __stack_top[];
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern std::uint32_t __data_load[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern void (*__preinit_array_start[])();
extern void (*__preinit_array_end[])();
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();

// librdimon: opens the semihosting console as stdin, stdout and stderr.
void initialise_monitor_handles();

void timer0_irq_handler();  // platform.cpp
[[noreturn]] void reset_handler();
void hard_fault_handler();
[[noreturn]] void unexpected_exception_handler();

}  // extern "C"

// The program's main, declared under another name: C++ forbids calling main by its own.
int application_main() asm("main");

namespace {

using intgrid::cortex_m3::semihosting::write0;

// QEMU's exit status after a fault: EX_SOFTWARE of sysexits.h, distinct from main's usual 1.
constexpr int fault_exit_status = 70;

// Configuration and Control Register: DIV_0_TRP makes an integer division by zero fault (as
// it traps on the host) instead of quietly giving 0.
constexpr std::uintptr_t scb_ccr_address = 0xE000ED14;
constexpr std::uint32_t ccr_div_0_trp = 1u << 4;

// Writes "<label>0x<8 hex digits>" without the C library, which a fault may have broken.
void write_hex(const char* label, std::uint32_t value) {
  write0(label);
  char digits[11] = "0x";
  for (int i = 0; i < 8; ++i) digits[2 + i] = "0123456789abcdef"[(value >> (28 - 4 * i)) & 0xFu];
  digits[10] = '\0';
  write0(digits);
}

std::uint32_t read_word(std::uintptr_t address) {
  return *reinterpret_cast<volatile std::uint32_t*>(address);
}

}  // namespace

extern "C" {

void reset_handler() {
  const std::size_t data_words = static_cast<std::size_t>(__data_end - __data_start);
  for (std::size_t i = 0; i < data_words; ++i) __data_start[i] = __data_load[i];
  for (std::uint32_t* word = __bss_start; word != __bss_end; ++word) *word = 0;

  *reinterpret_cast<volatile std::uint32_t*>(scb_ccr_address) |= ccr_div_0_trp;
  intgrid::cortex_m3::start_instruction_counter();
  initialise_monitor_handles();  // before the constructors, which may print

  for (auto* constructor = __preinit_array_start; constructor != __preinit_array_end; ++constructor)
    (*constructor)();
  for (auto* constructor = __init_array_start; constructor != __init_array_end; ++constructor)
    (*constructor)();

  // exit runs the atexit handlers (static destructors), flushes stdio, then _exit ends QEMU.
  std::exit(application_main());
}

// Passes report_hard_fault the frame the core stacked on entry (r0-r3, r12, lr, pc, xpsr), on
// MSP or PSP as EXC_RETURN bit 2 tells.
[[gnu::naked]] void hard_fault_handler() {
  asm volatile(
      "tst lr, #4\n\t"
      "ite eq\n\t"
      "mrseq r0, msp\n\t"
      "mrsne r0, psp\n\t"
      "b report_hard_fault");
}

[[gnu::used, noreturn]] void report_hard_fault(const std::uint32_t* stacked_frame) {
  write_hex("\nHardFault: pc ", stacked_frame[6]);
  write_hex(" lr ", stacked_frame[5]);
  write_hex(" cfsr ", read_word(0xE000ED28));
  write_hex(" hfsr ", read_word(0xE000ED2C));
  write_hex(" bfar ", read_word(0xE000ED38));
  write0("\n");
  intgrid::cortex_m3::semihosting::exit(fault_exit_status);
}

void unexpected_exception_handler() {
  std::uint32_t ipsr;
  asm volatile("mrs %0, ipsr" : "=r"(ipsr));
  write_hex("\nunexpected exception ", ipsr);
  write0("\n");
  intgrid::cortex_m3::semihosting::exit(fault_exit_status);
}

}  // extern "C"

namespace {

// 16 system exceptions, then the mps2-an385's 32 external interrupts.
constexpr std::size_t irq_count = 32;
constexpr std::size_t timer0_irq = 8;

union VectorEntry {
  const void* initial_stack_pointer;
  void (*handler)();
};

constexpr std::array<VectorEntry, 16 + irq_count> make_vector_table() {
  std::array<VectorEntry, 16 + irq_count> table{};
  for (VectorEntry& entry : table) entry.handler = unexpected_exception_handler;
  table[0].initial_stack_pointer = __stack_top;
  table[1].handler = reset_handler;
  table[3].handler = hard_fault_handler;
  table[16 + timer0_irq].handler = timer0_irq_handler;
  return table;
}

// constinit: built at compile time, so it lands in .vectors rather than in .bss.
[[gnu::used, gnu::section(".vectors")]] constinit const std::array<VectorEntry, 16 + irq_count>
    vector_table = make_vector_table();

}  // namespace
