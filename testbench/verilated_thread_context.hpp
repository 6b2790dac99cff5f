// The Verilator runtime's per-thread context, set from one place.
#pragma once

class VerilatedContext;

namespace intgrid::tb {

// Makes `context` the calling thread's Verilator context. Verilator's runtime looks models up in
// the thread's context: with several models alive, it must be the model's own whenever that model
// is built or destroyed (otherwise destruction deadlocks). Compiled in its own file, without
// UBSan's null check: GCC 12 at -O2 reports the inlined write to Verilator's thread_local as
// "member access within null pointer" (a false positive of GCC's check on extern TLS objects).
void use_verilated_context(VerilatedContext* context);

}  // namespace intgrid::tb
