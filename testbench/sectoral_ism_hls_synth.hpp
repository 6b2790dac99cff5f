// The top functions of the sectoral ISM for an HLS tool, one per configuration, defined in
// sectoral_ism_hls_synth.cpp (compiled with __SYNTHESIS__, as the tool sees it).
#pragma once

#include <cstdint>

#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"

namespace intgrid::hls_synth {

// One reading in (reading[0], the port's reading_bits), every cell's index out, ring-major.
void sectoral_ism_cone16(
    const std::uint16_t reading[1],
    std::int8_t cells[hw::SectoralIsmCone16::rings * hw::SectoralIsmCone16::bins]);
void sectoral_ism_cone12(
    const std::uint16_t reading[1],
    std::int8_t cells[hw::SectoralIsmCone12::rings * hw::SectoralIsmCone12::bins]);

}  // namespace intgrid::hls_synth
