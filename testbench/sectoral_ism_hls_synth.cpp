// hls/sectoral_ism.hpp as an HLS tool sees it (__SYNTHESIS__ defined, the HLS pragmas expanded):
// the top functions an HLS run synthesizes (`set_top sectoral_ism_cone16`), and the kernel
// template instantiated for golden's layout, which must compile cleanly.
//
// A top is free running (no start/done handshake, like rtl/sectoral_ism.sv): each call takes one
// reading from an AXI4-Stream port and writes the rings * bins indices, ring-major, to another,
// each cell once and in order (which a stream port requires). Ports are built-in integers of
// byte widths (AXI4-Stream data is whole bytes): the reading's 16 bits, an index in 8 bits.
#ifndef __SYNTHESIS__
#error "sectoral_ism_hls_synth.cpp must be compiled with __SYNTHESIS__ defined"
#endif

#include "testbench/sectoral_ism_hls_synth.hpp"

#include <cstdint>

#include "hls/hls_pragma.hpp"
#include "hls/sectoral_ism.hpp"

namespace intgrid::hls {

template void sectoral_ism_kernel<hw::SectoralIsmCone16, std::int16_t>(
    std::uint32_t, std::int16_t[hw::SectoralIsmCone16::rings * hw::SectoralIsmCone16::bins]);
template void sectoral_ism_kernel<hw::SectoralIsmCone12, std::int16_t>(
    std::uint32_t, std::int16_t[hw::SectoralIsmCone12::rings * hw::SectoralIsmCone12::bins]);

}  // namespace intgrid::hls

namespace intgrid::hls_synth {

// The interface pragmas belong in the top function itself (they name its arguments).
#define INTGRID_SECTORAL_ISM_TOP(name, Config)                                                 \
  void name(const std::uint16_t reading[1], std::int8_t cells[Config::rings * Config::bins]) { \
    INTGRID_HLS_PRAGMA("HLS INTERFACE mode=axis port=reading")                                 \
    INTGRID_HLS_PRAGMA("HLS INTERFACE mode=axis port=cells")                                   \
    INTGRID_HLS_PRAGMA("HLS INTERFACE mode=ap_ctrl_none port=return")                          \
    static_assert(Config::reading_bits <= 16 && Config::index_bits <= 8, "port widths");       \
    hls::sectoral_ism_kernel<Config>(reading[0], cells);                                       \
  }

INTGRID_SECTORAL_ISM_TOP(sectoral_ism_cone16, hw::SectoralIsmCone16)
INTGRID_SECTORAL_ISM_TOP(sectoral_ism_cone12, hw::SectoralIsmCone12)
#undef INTGRID_SECTORAL_ISM_TOP

}  // namespace intgrid::hls_synth
