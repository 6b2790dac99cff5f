#include "testbench/verilated_thread_context.hpp"

#include <verilated.h>

namespace intgrid::tb {

void use_verilated_context(VerilatedContext* context) {
  Verilated::threadContextp(context);
}

}  // namespace intgrid::tb
