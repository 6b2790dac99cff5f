#include "testbench/cortex_m3/semihosting.hpp"

namespace intgrid::cortex_m3::semihosting {
namespace {

enum class Operation : std::uint32_t {
  write0 = 0x04,
  exit = 0x18,
  exit_extended = 0x20,
};

// Reasons of SYS_EXIT (Arm semihosting specification, "ADP_Stopped_*").
constexpr std::uint32_t application_exit = 0x20026;
constexpr std::uint32_t run_time_error = 0x20023;

std::uint32_t call(Operation operation, const void* argument) {
  std::uint32_t result;
  asm volatile(
      "mov r0, %1\n\t"
      "mov r1, %2\n\t"
      "bkpt 0xab\n\t"
      "mov %0, r0"
      : "=r"(result)
      : "r"(static_cast<std::uint32_t>(operation)), "r"(argument)
      : "r0", "r1", "memory");
  return result;
}

}  // namespace

void write0(const char* text) {
  call(Operation::write0, text);
}

void exit(int status) {
  // QEMU 7.2 takes an A32/T32 guest's exit status only from SYS_EXIT_EXTENDED
  // {ADP_Stopped_ApplicationExit, status}; plain SYS_EXIT gives 0 for ApplicationExit, else 1.
  const std::uint32_t parameters[2] = {application_exit, static_cast<std::uint32_t>(status)};
  call(Operation::exit_extended, parameters);
  // Only reached on a host without SYS_EXIT_EXTENDED: keep at least zero versus non-zero.
  const std::uint32_t reason = status == 0 ? application_exit : run_time_error;
  call(Operation::exit, reinterpret_cast<const void*>(reason));
  for (;;) {
  }
}

}  // namespace intgrid::cortex_m3::semihosting
