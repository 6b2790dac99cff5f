// newlib system calls that the board defines itself, and what the C runtime's start files would
// define; librdimon provides the other system calls (write, open, ...) over semihosting.
#include <cerrno>
#include <cstddef>

#include "testbench/cortex_m3/platform.hpp"
#include "testbench/cortex_m3/semihosting.hpp"

extern "C" {

// Heap bounds from mps2_an385.ld.
extern char __heap_start[];
extern char __heap_end[];

}  // extern "C"

namespace {
constinit char* heap_top = __heap_start;  // what _sbrk has handed to malloc ends here
}  // namespace

std::size_t intgrid::cortex_m3::heap_bytes() {
  return static_cast<std::size_t>(heap_top - __heap_start);
}

extern "C" {

// malloc's memory: the heap region of the linker script. librdimon's weak _sbrk would bound
// the heap by the stack pointer, which here lies below the heap (SSRAM2&3 versus PSRAM).
void* _sbrk(std::ptrdiff_t increment) {
  if (increment > __heap_end - heap_top || increment < __heap_start - heap_top) {
    errno = ENOMEM;
    return reinterpret_cast<void*>(-1);
  }
  char* const previous_top = heap_top;
  heap_top += increment;
  return previous_top;
}

// exit() ends here after the atexit handlers and the stdio flush: QEMU exits with `status`.
[[noreturn]] void _exit(int status) {
  intgrid::cortex_m3::semihosting::exit(status);
}

// Two symbols of the C runtime's start files (crti.o, crtbegin.o), which -nostartfiles leaves
// out: _fini, called last by __libc_fini_array that newlib registers with atexit (nothing to do
// here), and __dso_handle, the module handle static destructors register with (__aeabi_atexit).
void _fini() {}
[[gnu::visibility("hidden")]] void* __dso_handle = &__dso_handle;

}  // extern "C"
