// Arm semihosting calls (BKPT 0xAB on M-profile), served by QEMU with
// -semihosting-config enable=on. Printing goes through newlib's printf (librdimon); these calls
// are for the paths where the C library cannot be trusted: exit and fault reports.
#pragma once

#include <cstdint>

namespace intgrid::cortex_m3::semihosting {

// Writes a NUL-terminated string to the host's console (SYS_WRITE0): QEMU 7.2 prints it on its
// stderr, while printf's stdout and stderr (librdimon) go to QEMU's stdout and stderr.
void write0(const char* text);

// Ends the simulation; QEMU exits with `status` (SYS_EXIT_EXTENDED).
[[noreturn]] void exit(int status);

}  // namespace intgrid::cortex_m3::semihosting
