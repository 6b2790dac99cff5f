// Entry points into mapping_engine_hls_synth.cpp, the HLS header compiled with __SYNTHESIS__.
#pragma once

#include <cstdint>

#include "hls/mapping_engine.hpp"

namespace intgrid::hls_synth {

// The engine at the sizes of the bundled log's settings (8-bit indices, a 256 x 256 tile, 30 m
// in 6 mm bins, 2^14 tail cells) as an HLS tool sees it.
using MappingEngineB8T8 = hls::MappingEngine<8, 8, 5002, 16384>;

// One reading of a straight wall ahead through the synthesized header; true when the cells
// along it took the ISM's core and the wall its tail.
bool mapping_engine_b8_t8_self_check();

// The top function for an HLS tool: a scan's `count` readings (at most 1024) inserted into the
// engine's tile, one cell a cycle.
void mapping_engine_b8_t8(MappingEngineB8T8& engine, const hls::ScanPose& pose,
                          const hls::RangeReading readings[1024], int count);

}  // namespace intgrid::hls_synth
