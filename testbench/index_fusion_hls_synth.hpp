// Entry points into index_fusion_hls_synth.cpp, the HLS header compiled with __SYNTHESIS__.
#pragma once

#include <cstdint>

#include "hls/index_fusion.hpp"

namespace intgrid::hls_synth {

std::uint32_t saturating_add_b8(std::uint32_t a, std::uint32_t b);
hls::Beat<12, 8> fuse_beat_b12_l8(const hls::Beat<12, 8>& a, const hls::Beat<12, 8>& b);
// Accumulates a fixed pattern into a tile and checks a few cells; true when they match.
bool tile_b8_l8_self_check();

// The top function for an HLS tool at the RTL's default parameters (B = 8, LANES = 8): one beat
// of each input stream in, the fused beat out, one beat per call and per cycle.
void index_fusion_b8_l8(const std::uint64_t a[1], const std::uint64_t b[1], std::uint64_t y[1]);

}  // namespace intgrid::hls_synth
